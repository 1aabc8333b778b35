#pragma once
// One trajectory goal (what a follow_joint_trajectory action goal becomes):
// its tolerances and its outcome, written by the controller's real-time
// thread and read by anyone holding it. Result codes are
// control_msgs/FollowJointTrajectoryResult's.
#include <atomic>
#include <string>

#include "servoloop/controllers/joint_trajectory_controller/trajectory_tolerances.hpp"
#include "servoloop/realtime/action_registry.hpp"

namespace servoloop::controllers::joint_trajectory_controller {

// pending, active, succeeded, aborted (a tolerance was violated, or the
// trajectory was in the past), preempted (replaced by a newer trajectory or
// goal, or the controller stopped), canceled (by its sender; the joints stop
// within stop_trajectory_duration), rejected (refused before it started).
using GoalStatus = servoloop::realtime::GoalState;

// control_msgs/FollowJointTrajectoryResult error codes.
enum class TrajectoryErrorCode : int {
  successful = 0,
  invalid_goal = -1,
  invalid_joints = -2,
  old_header_timestamp = -3,
  path_tolerance_violated = -4,
  goal_tolerance_violated = -5,
};

class TrajectoryGoal {
 public:
  explicit TrajectoryGoal(TrajectoryTolerances tolerances) : tolerances_(std::move(tolerances)) {}

  const TrajectoryTolerances& tolerances() const noexcept { return tolerances_; }

  // Any thread.
  GoalStatus status() const noexcept { return status_.load(std::memory_order_acquire); }
  TrajectoryErrorCode errorCode() const noexcept { return error_code_.load(std::memory_order_acquire); }
  bool done() const noexcept { return servoloop::realtime::goalDone(status()); }
  // Why it ended, in words (the error code's meaning, or why it was rejected).
  std::string errorString() const;
  // The joint that violated a tolerance (index into the controller's joints), or -1.
  int violatingJoint() const noexcept { return violating_joint_.load(std::memory_order_acquire); }

  // Any thread: ask the controller to stop following it.
  void requestCancel() noexcept { cancel_requested_.store(true, std::memory_order_release); }
  bool cancelRequested() const noexcept { return cancel_requested_.load(std::memory_order_acquire); }

  // The controller's side (real-time safe).
  void setActive() noexcept { status_.store(GoalStatus::active, std::memory_order_release); }
  // reason: why it ended when the code alone does not say (a string
  // literal, or anything else that outlives the goal; null: the code's
  // meaning).
  void finish(GoalStatus status, TrajectoryErrorCode code, int violating_joint = -1,
              const char* reason = nullptr) noexcept {
    reason_.store(reason, std::memory_order_relaxed);
    error_code_.store(code, std::memory_order_relaxed);
    violating_joint_.store(violating_joint, std::memory_order_relaxed);
    status_.store(status, std::memory_order_release);
  }
  // Non-real-time, before the goal is handed over.
  void reject(TrajectoryErrorCode code, std::string why) {
    rejection_ = std::move(why);
    finish(GoalStatus::rejected, code);
  }

 private:
  TrajectoryTolerances tolerances_;
  std::string rejection_;
  std::atomic<const char*> reason_{nullptr};
  std::atomic<GoalStatus> status_{GoalStatus::pending};
  std::atomic<TrajectoryErrorCode> error_code_{TrajectoryErrorCode::successful};
  std::atomic<int> violating_joint_{-1};
  std::atomic<bool> cancel_requested_{false};
};

}  // namespace servoloop::controllers::joint_trajectory_controller
