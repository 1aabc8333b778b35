// SafetySupervisor: latched safety states and the emergency-stop command override.
#include "servoloop/controller_manager/safety_supervisor.hpp"

#include <cmath>

#include <fmt/format.h>

#include "servoloop/hardware_interface/joint_interfaces.hpp"

namespace servoloop::controller_manager {

const char* toString(SafetyState state) noexcept {
  switch (state) {
    case SafetyState::running: return "running";
    case SafetyState::protective_stop: return "protective_stop";
    case SafetyState::emergency_stop: return "emergency_stop";
    case SafetyState::fault: return "fault";
  }
  return "unknown";
}

const char* toString(EmergencyStopSource source) noexcept {
  switch (source) {
    case EmergencyStopSource::command: return "command";
    case EmergencyStopSource::topic: return "topic";
    case EmergencyStopSource::hardware: return "hardware input";
  }
  return "unknown";
}

namespace {

// The command storage of every handle of one command interface. Looking the
// handles up records claims; they are cleared again, as nobody claimed them.
template <class Interface>
void collectCommands(hardware_interface::RobotHW& hw, std::vector<double*>& out,
                     std::vector<const double*>* positions = nullptr) {
  auto* interface = hw.get<Interface>();
  if (interface == nullptr) return;
  for (const std::string& name : interface->getNames()) {
    const auto handle = interface->getHandle(name);
    out.push_back(handle.getCommandPtr());
    if (positions != nullptr) positions->push_back(handle.getPositionPtr());
  }
  interface->clearClaims();
}

}  // namespace

SafetySupervisor::SafetySupervisor(hardware_interface::RobotHW& hw) : hw_(hw) {
  collectCommands<hardware_interface::EffortJointInterface>(hw, zeroed_commands_);
  collectCommands<hardware_interface::VelocityJointInterface>(hw, zeroed_commands_);
  collectCommands<hardware_interface::PositionJointInterface>(hw, position_commands_, &measured_positions_);
  held_positions_.assign(position_commands_.size(), 0.0);
}

bool SafetySupervisor::protectiveStopped() const noexcept {
  return protective_.load(std::memory_order_acquire) && !fault_.load(std::memory_order_acquire);
}

bool SafetySupervisor::emergencyStopSource(EmergencyStopSource* source) const noexcept {
  const std::uint8_t estop = estop_.load(std::memory_order_acquire);
  if (estop == kReleased) return false;
  if (source != nullptr) *source = static_cast<EmergencyStopSource>(estop - 1);
  return true;
}

bool SafetySupervisor::startsForbidden() const noexcept {
  return protective_.load(std::memory_order_acquire) || fault_.load(std::memory_order_acquire);
}

SafetyState SafetySupervisor::state() const noexcept {
  if (fault_.load(std::memory_order_acquire)) return SafetyState::fault;
  if (emergencyStopLatched() || hardware_input_.load(std::memory_order_acquire)) {
    return SafetyState::emergency_stop;
  }
  if (protective_.load(std::memory_order_acquire)) return SafetyState::protective_stop;
  return SafetyState::running;
}

void SafetySupervisor::engageEmergencyStop(EmergencyStopSource source) noexcept {
  // One engagement per latch, also when the loop's poll and a racing release
  // both engage.
  std::uint8_t released = kReleased;
  const auto latched = static_cast<std::uint8_t>(1 + static_cast<std::uint8_t>(source));
  if (!estop_.compare_exchange_strong(released, latched, std::memory_order_seq_cst)) return;
  emergency_stops_.fetch_add(1, std::memory_order_relaxed);
}

bool SafetySupervisor::releaseEmergencyStop(std::string* why) {
  if (hardware_input_.load(std::memory_order_acquire)) {
    if (why != nullptr) {
      *why = "the hardware's own emergency-stop input is still active; release it on the robot (the button, the "
             "safety relay) first, then run `servoloop control estop off` again";
    }
    return false;
  }
  estop_.store(kReleased, std::memory_order_seq_cst);
  // The input may have been pressed since the check: a poll that saw it
  // while the latch was still set did not latch again, so latch it here.
  // (The loop never sends commands while its last poll saw the input, latch
  // or not: overrideCommands.)
  if (hardware_input_.load(std::memory_order_seq_cst)) {
    engageEmergencyStop(EmergencyStopSource::hardware);
    if (why != nullptr) *why = "the hardware's own emergency-stop input was pressed again; release it on the robot first";
    return false;
  }
  return true;
}

void SafetySupervisor::clearStop() noexcept {
  failed_result_.store(ReturnType::error, std::memory_order_relaxed);
  fault_.store(false, std::memory_order_release);
  protective_.store(false, std::memory_order_release);
}

std::string SafetySupervisor::emergencyStopText() const {
  const std::uint8_t estop = estop_.load(std::memory_order_acquire);
  const bool input = hardware_input_.load(std::memory_order_acquire);
  if (estop == kReleased && !input) return {};
  const EmergencyStopSource source =
      estop == kReleased ? EmergencyStopSource::hardware : static_cast<EmergencyStopSource>(estop - 1);
  return fmt::format("emergency stop engaged by {}: effort and velocity commands are 0, position commands hold; {}",
                     toString(source),
                     input ? "the hardware's input is still active: release it on the robot, then run `servoloop "
                             "control estop off`"
                           : "release with `servoloop control estop off`");
}

std::string SafetySupervisor::reason() const {
  const SafetyState current = state();
  const auto cause = [this] {
    const ReturnType result = failed_result_.load(std::memory_order_relaxed);
    return fmt::format("the hardware's {}() returned {} at t = {:.3f} s", toString(failed_call_.load(std::memory_order_relaxed)),
                       result == ReturnType::deactivate ? "deactivate" : "an error",
                       failed_time_s_.load(std::memory_order_relaxed));
  };
  switch (current) {
    case SafetyState::running: return {};
    case SafetyState::emergency_stop: return emergencyStopText();
    case SafetyState::protective_stop:
      return fmt::format("protective stop: {}; the controllers that command the robot were stopped; after fixing "
                         "the cause run `servoloop control recover`",
                         cause());
    case SafetyState::fault:
      return fmt::format("fault: the control loop stopped because {}; after fixing the cause run `servoloop control "
                         "recover` to run it again",
                         cause());
  }
  return {};
}

void SafetySupervisor::refreshHardwareInput() noexcept {
  hardware_input_.store(hw_.emergencyStopInput(), std::memory_order_seq_cst);
}

void SafetySupervisor::pollHardwareInput() noexcept {
  const bool input = hw_.emergencyStopInput();  // noexcept
  // The common case, an input that stays released, writes nothing (a
  // sequentially consistent store is a full barrier, every cycle); a pressed
  // input is stored every cycle, ordered before the latch it engages, as the
  // release's check of it needs.
  if (!input && !hardware_input_.load(std::memory_order_relaxed)) return;
  hardware_input_.store(input, std::memory_order_seq_cst);
  if (input) engageEmergencyStop(EmergencyStopSource::hardware);
}

bool SafetySupervisor::hardwareFailed(HardwareCall call, ReturnType result, Time time) noexcept {
  if (result == ReturnType::ok) return false;
  if (protective_.load(std::memory_order_relaxed) || fault_.load(std::memory_order_relaxed)) return false;
  failed_call_.store(call, std::memory_order_relaxed);
  failed_result_.store(result, std::memory_order_relaxed);
  failed_time_s_.store(time.seconds, std::memory_order_relaxed);
  // deactivate stops the loop at the end of the cycle: hardwareStopped() follows.
  if (result == ReturnType::deactivate) return false;
  protective_.store(true, std::memory_order_release);
  protective_stops_.fetch_add(1, std::memory_order_relaxed);
  return true;
}

bool SafetySupervisor::hardwareStopped(Time time) noexcept {
  if (fault_.load(std::memory_order_relaxed)) return false;
  // A deactivate already recorded its call; a stop without one (too many
  // failed cycles) keeps the error that started the protective stop.
  const bool already_contained = protective_.load(std::memory_order_relaxed);
  if (!already_contained && failed_result_.load(std::memory_order_relaxed) != ReturnType::deactivate) {
    failed_result_.store(ReturnType::deactivate, std::memory_order_relaxed);
    failed_time_s_.store(time.seconds, std::memory_order_relaxed);
  }
  fault_.store(true, std::memory_order_release);
  return !already_contained;
}

// Where each position-commanded joint is (its command when the position is
// not known), as a faulted controller's safe output holds it.
void SafetySupervisor::latchHeldPositions() noexcept {
  for (std::size_t i = 0; i < position_commands_.size(); ++i) {
    const double* measured = measured_positions_[i];
    held_positions_[i] = measured != nullptr && std::isfinite(*measured) ? *measured : *position_commands_[i];
  }
  holding_ = true;
}

void SafetySupervisor::overrideCommands() noexcept {
  // The input as this cycle's poll saw it counts as well as the latch: a
  // release racing the poll can clear the latch, never this thread's own
  // reading of the input.
  if (estop_.load(std::memory_order_acquire) == kReleased && !hardware_input_.load(std::memory_order_relaxed)) {
    holding_ = false;
    return;
  }
  if (!holding_) latchHeldPositions();
  for (double* command : zeroed_commands_) *command = 0.0;
  for (std::size_t i = 0; i < position_commands_.size(); ++i) *position_commands_[i] = held_positions_[i];
}

}  // namespace servoloop::controller_manager
