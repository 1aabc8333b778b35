// ControlLoop: the pieces of a cycle both loop kinds share.
#include "servoloop/controller_manager/control_loop.hpp"

#include "servoloop/controller_manager/controller_manager.hpp"
#include "servoloop/controller_manager/loop_clock.hpp"
#include "servoloop/controller_manager/safety_supervisor.hpp"
#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"

#include <cmath>
#include <cstddef>

namespace servoloop::controller_manager {

ControlLoop::ControlLoop(hardware_interface::RobotHW& robot_hw, ControllerManager& manager,
                         const LoopCommonOptions& options, Duration control_period)
    : robot_hw_(robot_hw), manager_(manager), options_(options), control_period_(control_period) {
  // The joint states read() fills, checked after every read(): a NaN or
  // infinite one makes the read an error (see control_loop.hpp).
  if (auto* states = robot_hw_.get<hardware_interface::JointStateInterface>()) {
    for (const std::string& name : states->getNames()) {
      const hardware_interface::JointStateHandle handle = states->getHandle(name);
      if (!handle.valid()) continue;
      joint_state_names_.push_back(name);
      joint_state_values_.push_back(handle.getPositionPtr());
      joint_state_values_.push_back(handle.getVelocityPtr());
      joint_state_values_.push_back(handle.getEffortPtr());
    }
  }
  // A loop times its cycles (and so the controllers' updates) unless it says
  // otherwise (setPhaseTiming); the bare manager does not time them.
  manager_.setUpdateTiming(time_phases_);
  loop_clock::prepareCycleClock();  // the phases' clock, calibrated here, not on the real-time thread
}

bool ControlLoop::logHardwareErrorReport() {
  const std::optional<HardwareErrorReport> report = takeHardwareErrorReport();
  if (!report) return false;
  logger().error("control loop: {} ({} hardware errors counted so far)", report->message(),
                 statistics_.snapshot().hardware_errors);
  return true;
}

namespace {
// What a controller stopped for a hardware failure is told (fixed text: the
// real-time thread formats nothing).
const char* protectiveStopCause(HardwareCall call) noexcept {
  switch (call) {
    case HardwareCall::read: return "its read() returned an error (protective stop)";
    case HardwareCall::write: return "its write() returned an error (protective stop)";
    case HardwareCall::step: return "its step() returned an error (protective stop)";
  }
  return "protective stop";
}

constexpr const char* kJointStateQuantities[3] = {"position", "velocity", "effort"};
}  // namespace

void ControlLoop::recordFailure(HardwareCall call, ReturnType result, Time time, std::uint64_t cycle,
                                const NonFiniteJointState* non_finite) noexcept {
  if (hardware_errors_.record(call, result, time, cycle, non_finite)) statistics_.recordHardwareError();
  if (options_.safety != nullptr && options_.safety->hardwareFailed(call, result, time)) {
    manager_.containHardwareFailure(time, non_finite != nullptr
                                              ? "its read() gave a joint state that is not a finite number "
                                                "(protective stop)"
                                              : protectiveStopCause(call));
  }
  if (result == ReturnType::deactivate) {
    // The loop stops at the end of this cycle (finishCycle); the fault and
    // its containment come now, so a deactivating read() is followed by no
    // update or command of the controllers it stops.
    deactivate_this_cycle_ = true;
    if (options_.safety != nullptr && options_.safety->hardwareStopped(time)) {
      manager_.containHardwareFailure(time, "it stopped the control loop (fault)");
    }
  }
}

void ControlLoop::setPhaseTiming(bool timed) noexcept {
  time_phases_ = timed;
  manager_.setUpdateTiming(timed);
}

void ControlLoop::requestStatisticsReset() noexcept {
  manager_.requestUpdateTimingReset();
  statistics_.requestReset();
}

void ControlLoop::sampleUpdateTiming() noexcept {
  const bool timed = time_phases_ && update_timing_countdown_ == 0;
  update_timing_countdown_ = timed ? kUpdateTimingStride - 1 : update_timing_countdown_ - 1;
  manager_.setUpdateTiming(timed);
}

void ControlLoop::applyRequestedStatisticsReset() noexcept {
  // The first cycle after a reset times the controllers too, so a reset
  // followed by one cycle has figures for every part of it.
  if (statistics_.applyRequestedReset()) update_timing_countdown_ = 0;
}

ReturnType ControlLoop::readHardware(Time time, Duration period, std::uint64_t cycle) noexcept {
  ReturnType result = ReturnType::error;
  const std::int64_t start_ns = time_phases_ ? loop_clock::cycleClockNs() : 0;
  beginHardwareCall(HardwareCall::read);
  try {
    result = robot_hw_.read(time, period);
  } catch (...) {
    // read() must not throw; containing it keeps the loop (and the robot's
    // other joints) under control. It is reported as an error of this call.
  }
  endHardwareCall();
  if (time_phases_) statistics_.recordRead(loop_clock::cycleClockNs() - start_ns);
  NonFiniteJointState non_finite;
  if (result == ReturnType::ok && !jointStatesFinite(&non_finite)) [[unlikely]] {
    // What read() left is no state of a robot: a failed read, named.
    result = ReturnType::error;
    recordFailure(HardwareCall::read, result, time, cycle, &non_finite);
  } else {
    recordHardwareResult(HardwareCall::read, result, time, cycle);
  }
  if (options_.safety != nullptr) options_.safety->pollHardwareInput();
  return result;
}

bool ControlLoop::jointStatesFinite(NonFiniteJointState* found) const noexcept {
  // One pass without branches over the values; the culprit is looked for
  // only when there is one.
  bool all_finite = true;
  for (const double* value : joint_state_values_) all_finite &= std::isfinite(*value);
  if (all_finite) [[likely]] return true;
  for (std::size_t i = 0; i < joint_state_values_.size(); ++i) {
    const double value = *joint_state_values_[i];
    if (std::isfinite(value)) continue;
    found->joint = &joint_state_names_[i / 3];
    found->quantity = kJointStateQuantities[i % 3];
    found->value = value;
    return false;
  }
  return false;  // (changed under us: some value was not finite a moment ago)
}

ReturnType ControlLoop::writeHardware(Time time, Duration period, std::uint64_t cycle) noexcept {
  // Every write, also the physics steps between two control updates.
  if (options_.safety != nullptr) options_.safety->overrideCommands();
  ReturnType result = ReturnType::error;
  const std::int64_t start_ns = time_phases_ ? loop_clock::cycleClockNs() : 0;
  beginHardwareCall(HardwareCall::write);
  try {
    result = robot_hw_.write(time, period);
  } catch (...) {
    // As in readHardware: counted and reported as an error of write().
  }
  endHardwareCall();
  if (time_phases_) statistics_.recordWrite(loop_clock::cycleClockNs() - start_ns);
  recordHardwareResult(HardwareCall::write, result, time, cycle);
  return result;
}

void ControlLoop::setBusTime(Time time) noexcept {
  if (options_.topic_bus != nullptr) options_.topic_bus->setTime(time);
}

void ControlLoop::updateControllers(Time time, Duration period) noexcept {
  manager_.update(time, period);
  if (options_.cycle_hook != nullptr) options_.cycle_hook->afterUpdate(time, period);
}

void ControlLoop::finishCycle(Time time) noexcept {
  hardware_errors_.endCycle();
  const bool too_many_failures = options_.stop_after_failed_cycles > 0 &&
                                 hardware_errors_.consecutiveFailedCycles() >= options_.stop_after_failed_cycles;
  if (deactivate_this_cycle_ || too_many_failures) {
    if (options_.safety != nullptr && options_.safety->hardwareStopped(time)) {
      manager_.containHardwareFailure(time, "it stopped the control loop (fault)");
    }
    hardware_stop_.store(true, std::memory_order_release);
  }
  deactivate_this_cycle_ = false;
}

bool ControlLoop::shouldStop(const std::atomic<bool>* external_stop) const noexcept {
  return stop_requested_.load(std::memory_order_acquire) || hardware_stop_.load(std::memory_order_relaxed) ||
         (external_stop != nullptr && external_stop->load(std::memory_order_acquire));
}

}  // namespace servoloop::controller_manager
