#include "servoloop/controller_manager/controller_base.hpp"

#include <cmath>

#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/controller_manager/controller_spec.hpp"

namespace servoloop::controller_manager {

const char* toString(ControllerState state) noexcept {
  switch (state) {
    case ControllerState::constructed: return "constructed";
    case ControllerState::initialized: return "initialized";
    case ControllerState::running: return "running";
    case ControllerState::stopped: return "stopped";
    case ControllerState::failed: return "failed";
  }
  return "unknown";
}

const char* toString(FaultKind kind) noexcept {
  switch (kind) {
    case FaultKind::starting_threw: return "starting() threw";
    case FaultKind::update_threw: return "update() threw";
    case FaultKind::update_returned_error: return "update() returned ReturnType::error";
    case FaultKind::non_finite_command: return "a command was not finite";
    case FaultKind::stopping_threw: return "stopping() threw";
    case FaultKind::hardware_failed: return "the hardware failed";
  }
  return "unknown fault";
}

ControllerBase::~ControllerBase() = default;

bool ControllerBase::startRequest(const Time& time) {
  const ControllerState current = state();
  if (current != ControllerState::initialized && current != ControllerState::stopped &&
      current != ControllerState::failed) {
    return false;
  }
  starting(time);
  state_.store(ControllerState::running, std::memory_order_release);
  return true;
}

bool ControllerBase::stopRequest(const Time& time) {
  if (state() != ControllerState::running) return false;
  state_.store(ControllerState::stopped, std::memory_order_release);
  stopping(time);
  return true;
}

void ControllerBase::abortRequest() noexcept {
  writeSafeCommands();
  try {
    setSafeOutput();
  } catch (...) {
    // The manager's safe values are already written; a failing hook cannot undo them.
  }
  state_.store(ControllerState::failed, std::memory_order_release);
}

void ControllerBase::writeSafeCommands() noexcept {
  for (const ClaimedCommand& claimed : claimed_commands_) {
    if (claimed.safe == SafeCommand::zero) {
      *claimed.command = 0.0;  // no effort, no velocity
    } else if (claimed.position != nullptr && std::isfinite(*claimed.position)) {
      *claimed.command = *claimed.position;  // hold where the joint is
    } else if (!std::isfinite(*claimed.command)) {
      // Nothing sane to hold: the measurement is broken too. A finite last
      // command is kept rather than sending the joint to zero.
      *claimed.command = 0.0;
    }
  }
}

namespace detail {

std::string joinInterfaceNames(const std::vector<std::string>& names) {
  if (names.empty()) return "none";
  std::string joined;
  for (const auto& name : names) joined += (joined.empty() ? "" : ", ") + name;
  return joined;
}

std::string missingInterfaceMessage(const std::string& controller_name,
                                    const std::vector<std::string>& missing,
                                    const std::vector<std::string>& offered) {
  return "controller '" + controller_name + "' needs " + joinInterfaceNames(missing) +
         ", which the hardware does not offer (it offers: " + joinInterfaceNames(offered) +
         "); choose a controller type for one of the offered interfaces, or add a "
         "<hardwareInterface> for it to the joint's <transmission> in the URDF";
}

}  // namespace detail
}  // namespace servoloop::controller_manager
