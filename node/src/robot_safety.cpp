// A robot's safety states: the emergency stop, protective stops and faults,
// and recovering from them.
#include <algorithm>
#include <chrono>
#include <set>
#include <thread>

#include <fmt/format.h>

#include "servoloop/core/logging.hpp"
#include "servoloop/node/robot_instance.hpp"

namespace servoloop::node {
namespace {

// How long recover() waits for the loop: to resume, to run its confirming
// cycles, to carry out a switch (wall time).
constexpr double kRecoverySwitchTimeout_s = 5.0;

}  // namespace

controller_manager::ServiceResult RobotInstance::setEmergencyStop(bool engaged,
                                                                  controller_manager::EmergencyStopSource source) {
  if (engaged) {
    const bool was_latched = safety_->emergencyStopLatched();
    safety_->engageEmergencyStop(source);
    if (!was_latched) logger().warn("robot '{}': {}", namespace_, safety_->emergencyStopText());
    return controller_manager::ServiceResult::success();
  }
  std::string why;
  {
    // While the loop stands after a fault nothing polls the hardware's input:
    // read it now (the loop cannot resume while this lock is held).
    std::lock_guard recovery(recovery_mutex_);
    if (waiting_for_recovery_) safety_->refreshHardwareInput();
  }
  if (!safety_->releaseEmergencyStop(&why)) {
    return controller_manager::ServiceResult::failure(fmt::format("robot '{}': the emergency stop stays engaged: {}", namespace_, why));
  }
  logger().info("robot '{}': emergency stop released; the robot is {}", namespace_,
                controller_manager::toString(safety_->state()));
  return controller_manager::ServiceResult::success();
}

void RobotInstance::logHardwareEmergencyStops() {
  const std::uint64_t stops = safety_->emergencyStops();
  if (stops == emergency_stops_seen_) return;
  emergency_stops_seen_ = stops;
  controller_manager::EmergencyStopSource source{};
  if (safety_->emergencyStopSource(&source) && source == controller_manager::EmergencyStopSource::hardware) {
    logger().warn("robot '{}': {}", namespace_, safety_->emergencyStopText());
  }
}

// Loop thread, after the hardware stopped the loop. False when the robot is
// being stopped instead.
bool RobotInstance::waitForRecovery() {
  logger().error("robot '{}': {}", namespace_, safety_->reason());
  std::unique_lock lock(recovery_mutex_);
  waiting_for_recovery_ = true;
  recovery_wake_.wait(lock, [this] { return recovery_requested_ || stop_requested_.load(); });
  waiting_for_recovery_ = false;
  if (stop_requested_.load()) return false;
  recovery_requested_ = false;
  // Cleared here, where the loop is sure to run again (not by recover(), whose
  // caller could otherwise see "running" for a loop that has ended).
  safety_->clearStop();
  loop_->clearHardwareStop();
  resumed_ = true;
  lock.unlock();
  recovery_wake_.notify_all();
  return true;
}

// False when the loop did not run `cycles` more cycles within timeout_s (it
// ended, or stalls). A statistics reset meanwhile restarts the count.
bool RobotInstance::waitForCycles(std::uint64_t cycles, double timeout_s) const {
  std::uint64_t last = loop_->statistics().cycles();
  std::uint64_t seen = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (seen < cycles) {
    if (finished() || std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    const std::uint64_t now = loop_->statistics().cycles();
    seen += now >= last ? now - last : now;  // counted from 0 again after a reset
    last = now;
  }
  return true;
}

// The controllers a protective stop or fault stopped, started again in one
// switch that stops whatever runs on their resources now (their fallbacks).
controller_manager::ServiceResult RobotInstance::restartStoppedControllers(std::vector<std::string>* restarted) {
  const std::vector<controller_manager::ControllerSpec> controllers = manager_->listControllers();
  std::vector<std::string> restart;
  std::set<std::string> resources;
  for (const controller_manager::ControllerSpec& controller : controllers) {
    if (controller.state != controller_manager::ControllerState::failed || controller.last_fault.empty() ||
        controller.last_fault_kind != controller_manager::FaultKind::hardware_failed) {
      continue;
    }
    restart.push_back(controller.name);
    for (const auto& claim : controller.claimed_resources) resources.insert(claim.resources.begin(), claim.resources.end());
  }
  if (restart.empty()) return controller_manager::ServiceResult::success();
  *restarted = restart;
  controller_manager::SwitchRequest request;
  request.start_controllers = restart;
  request.strictness = controller_manager::SwitchStrictness::STRICT;
  for (const controller_manager::ControllerSpec& controller : controllers) {
    if (controller.state != controller_manager::ControllerState::running) continue;
    for (const auto& claim : controller.claimed_resources) {
      const bool shares = std::any_of(claim.resources.begin(), claim.resources.end(),
                                      [&](const std::string& r) { return resources.count(r) != 0; });
      if (shares) {
        request.stop_controllers.push_back(controller.name);
        break;
      }
    }
  }
  request.timeout_s = kRecoverySwitchTimeout_s;
  return manager_->switchController(request);
}

std::string RobotInstance::switchRefusal(const controller_manager::SwitchRequest& request) const {
  using controller_manager::SafetyState;
  // Stopping is always allowed (the node stops its controllers on the way out, fault or not).
  if (request.start_controllers.empty() || !safety_->startsForbidden()) return {};
  // The decision is taken; what follows only words it.
  const SafetyState safety = safety_->state();
  const std::string why =
      safety == SafetyState::emergency_stop
          ? "a protective stop holds under the emergency stop; release the emergency stop, then, after fixing the "
            "protective stop's cause, run `servoloop control recover`"
          : safety_->reason();
  if (why.empty()) return fmt::format("robot '{}': a protective stop held when the switch was checked; try again", namespace_);
  return fmt::format("robot '{}': {}; no controller can start until then (stopping them is allowed)", namespace_, why);
}

controller_manager::ServiceResult RobotInstance::recover() {
  using controller_manager::SafetyState;
  using controller_manager::ServiceResult;
  if (safety_->emergencyStopLatched()) {
    return ServiceResult::failure(fmt::format(
        "robot '{}': the emergency stop is engaged; release it first with `servoloop control estop off`", namespace_));
  }
  const SafetyState before = safety_->state();
  if (before == SafetyState::running) return ServiceResult::success();
  if (finished() || !started()) {
    return ServiceResult::failure(fmt::format(
        "robot '{}': its control loop has ended (the run had a duration), so it cannot be recovered; launch again",
        namespace_));
  }
  manager_->processFaults();  // the stopped controllers' faults, drained and recorded
  if (before == SafetyState::fault) {
    // The loop's thread clears the fault when it runs again (waitForRecovery,
    // or in the world resumeIfRecoveryRequested, which the world loop's
    // thread calls once woken).
    std::unique_lock lock(recovery_mutex_);
    resumed_ = false;
    recovery_requested_ = true;
    recovery_wake_.notify_all();
    if (world_loop_ != nullptr) {
      lock.unlock();
      world_loop_->wake();
      lock.lock();
    }
    const bool resumed = recovery_wake_.wait_for(lock, std::chrono::duration<double>(kRecoverySwitchTimeout_s),
                                                 [this] { return resumed_ || stop_requested_.load(); });
    if (!resumed || stop_requested_.load()) {
      recovery_requested_ = false;
      return ServiceResult::failure(fmt::format("robot '{}': its control loop did not run again", namespace_));
    }
  } else {
    safety_->clearStop();
  }
  // The hardware must work for a few cycles before any controller drives it
  // again, and go on working once they do; a loop that does not cycle fails too.
  constexpr std::uint64_t kCyclesToConfirm = 5;
  const auto failedAgain = [&] {
    const bool cycled = waitForCycles(kCyclesToConfirm, kRecoverySwitchTimeout_s);
    return !cycled || safety_->state() != SafetyState::running;
  };
  if (failedAgain()) {
    return ServiceResult::failure(
        fmt::format("robot '{}': the hardware failed again at once: {}", namespace_, safety_->reason()));
  }
  std::vector<std::string> restarted;
  const ServiceResult started = restartStoppedControllers(&restarted);
  if (!started) {
    return ServiceResult::failure(fmt::format("robot '{}': recovered, but the stopped controllers did not start: {}",
                                              namespace_, started.message));
  }
  if (failedAgain()) {
    // A failure in the very cycle they started missed them: stop them again.
    controller_manager::SwitchRequest stop;
    stop.stop_controllers = restarted;
    stop.strictness = controller_manager::SwitchStrictness::BEST_EFFORT;
    stop.timeout_s = kRecoverySwitchTimeout_s;
    manager_->switchController(stop);
    return ServiceResult::failure(
        fmt::format("robot '{}': the hardware failed again at once: {}", namespace_, safety_->reason()));
  }
  logger().info("robot '{}': recovered from {}; the robot is running", namespace_, controller_manager::toString(before));
  return ServiceResult::success();
}

}  // namespace servoloop::node

namespace servoloop::node {

namespace {

const char* callName(controller_manager::HardwareCall call) {
  switch (call) {
    case controller_manager::HardwareCall::read: return "read";
    case controller_manager::HardwareCall::write: return "write";
    case controller_manager::HardwareCall::step: return "step";
  }
  return "hardware";
}

}  // namespace

void RobotInstance::watchHardware(std::chrono::steady_clock::time_point now) {
  if (!loop_) return;
  const controller_manager::ControlLoop::HardwareCallInProgress call = loop_->hardwareCallInProgress();
  std::lock_guard lock(stuck_mutex_);
  if (!call.in_call || call.number != watched_call_) {
    if (stuck_.load()) {
      stuck_.store(false);
      logger().info("robot '{}': its hardware's {}() returned after {:.1f} s; the robot runs on", namespace_,
                    stuck_call_, std::chrono::duration<double>(now - watched_since_).count());
    }
    watched_call_ = call.in_call ? call.number : 0;
    watched_since_ = now;
    stuck_call_ = callName(call.call);
    return;
  }
  const double limit_s = std::max(1.0, 20.0 * loop_->controlPeriod().seconds);
  const double seconds = std::chrono::duration<double>(now - watched_since_).count();
  if (!stuck_.load() && seconds >= limit_s) {
    stuck_.store(true);
    logger().error("robot '{}': its hardware's {}() has not returned for {:.1f} s; its controllers get no update "
                   "until it does, and nothing that needs a cycle of the robot can be carried out (the node and "
                   "its other robots run on)",
                   namespace_, stuck_call_, seconds);
  }
}

std::string RobotInstance::stuckReason() const {
  std::lock_guard lock(stuck_mutex_);
  if (!stuck_.load()) return {};
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - watched_since_).count();
  return fmt::format("its hardware's {}() has not returned for {:.1f} s", stuck_call_, seconds);
}

}  // namespace servoloop::node
