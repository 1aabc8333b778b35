#pragma once
// The goal, feedback and result types of the actions servoloop's controllers
// serve, with the field names of their ROS counterparts (control_msgs'
// FollowJointTrajectory.action and GripperCommand.action), so `servoloop action send` goals read the
// way ROS users write them. JSON forms: node/message_json.hpp.
#include <string>
#include <string_view>
#include <vector>

#include "servoloop/realtime/messages.hpp"

namespace servoloop::control_msgs {

// How far one joint may stray (FollowJointTrajectory's path and goal
// tolerances): > 0 replaces the controller's default, 0 keeps it, < 0 turns
// the check off.
struct JointTolerance {
  std::string name;
  double position = 0.0;
  double velocity = 0.0;
  double acceleration = 0.0;
};

struct FollowJointTrajectoryGoal {
  static constexpr std::string_view kActionType = "control_msgs/FollowJointTrajectory";
  trajectory_msgs::JointTrajectory trajectory;
  std::vector<JointTolerance> path_tolerance;
  std::vector<JointTolerance> goal_tolerance;
  double goal_time_tolerance = 0.0;  // s; 0 keeps the controller's goal_time
};

struct FollowJointTrajectoryFeedback {
  double stamp = 0.0;  // control time, s
  std::vector<std::string> joint_names;
  trajectory_msgs::JointTrajectoryPoint desired;
  trajectory_msgs::JointTrajectoryPoint actual;
  trajectory_msgs::JointTrajectoryPoint error;
};

struct FollowJointTrajectoryResult {
  // 0 SUCCESSFUL, -1 INVALID_GOAL, -2 INVALID_JOINTS, -3 OLD_HEADER_TIMESTAMP,
  // -4 PATH_TOLERANCE_VIOLATED, -5 GOAL_TOLERANCE_VIOLATED.
  int error_code = 0;
  std::string error_string;
};

// A gripper command: move the gripper joint to position (m or rad), pushing
// with at most max_effort (N or N·m; the effort controller's limit).
struct GripperCommand {
  double position = 0.0;
  double max_effort = 0.0;
};

struct GripperCommandGoal {
  static constexpr std::string_view kActionType = "control_msgs/GripperCommand";
  GripperCommand command;
};

// Feedback and result: where the gripper is, the effort it applies, whether
// it stopped moving short of the goal (stalled, e.g. on an object) and
// whether it reached the goal.
struct GripperCommandFeedback {
  double position = 0.0;
  double effort = 0.0;
  bool stalled = false;
  bool reached_goal = false;
};
using GripperCommandResult = GripperCommandFeedback;

}  // namespace servoloop::control_msgs
