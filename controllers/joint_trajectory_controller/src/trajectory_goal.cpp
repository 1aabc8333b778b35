#include "servoloop/controllers/joint_trajectory_controller/trajectory_goal.hpp"

namespace servoloop::controllers::joint_trajectory_controller {

std::string TrajectoryGoal::errorString() const {
  if (status() == GoalStatus::rejected) return rejection_;
  const std::string joint = violatingJoint() >= 0 ? " (joint " + std::to_string(violatingJoint()) + ")" : "";
  if (const char* reason = reason_.load(std::memory_order_relaxed)) return reason + joint;
  switch (errorCode()) {
    case TrajectoryErrorCode::successful: return "";
    case TrajectoryErrorCode::invalid_goal: return "invalid goal";
    case TrajectoryErrorCode::invalid_joints: return "the goal's joints do not match the controller's";
    case TrajectoryErrorCode::old_header_timestamp: return "every point of the trajectory was in the past";
    case TrajectoryErrorCode::path_tolerance_violated: return "a joint left the path tolerance" + joint;
    case TrajectoryErrorCode::goal_tolerance_violated:
      return "a joint was outside the goal tolerance after goal_time" + joint;
  }
  return "";
}

}  // namespace servoloop::controllers::joint_trajectory_controller
