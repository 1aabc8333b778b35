#pragma once
// Actions in JSON, for the node's socket and the command line: goals read
// from JSON (the form `servoloop action send` users write, as YAML or JSON),
// feedback and results written as JSON, for every action type servoloop's
// controllers serve (realtime/action_messages.hpp). Non-real-time.
//
// control_msgs/FollowJointTrajectory goal:
//   {trajectory: {joint_names: [...], points: [...]},     // trajectory_msgs/JointTrajectory
//    path_tolerance: [{name, position, velocity, acceleration}],
//    goal_tolerance: [...], goal_time_tolerance: 0.5}
// control_msgs/GripperCommand goal:
//   {command: {position: 0.02, max_effort: 10}}
// Errors throw servoloop::Error naming the action type and the field.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "servoloop/realtime/action_messages.hpp"
#include "servoloop/realtime/action_registry.hpp"

namespace servoloop::node {

// Action types with a JSON form, sorted.
std::vector<std::string> knownActionTypes();

void fromJson(const nlohmann::json& json, control_msgs::FollowJointTrajectoryGoal& out);
nlohmann::json toJson(const control_msgs::FollowJointTrajectoryFeedback& feedback);
nlohmann::json toJson(const control_msgs::FollowJointTrajectoryResult& result);
void fromJson(const nlohmann::json& json, control_msgs::GripperCommandGoal& out);
nlohmann::json toJson(const control_msgs::GripperCommandFeedback& feedback);  // also the result

// Sends a goal given as JSON to the action `name` of type `type` (empty: the
// action's own type). Throws servoloop::Error for an unknown action or type,
// a goal that does not read as the type's goal, or NaN/infinite numbers in it.
std::shared_ptr<realtime::ActionGoal> sendGoalJson(realtime::ActionRegistry& actions, std::string_view name,
                                                   std::string type, const nlohmann::json& goal);

// The goal's newest feedback as JSON (null when there is none yet), and its
// result as JSON; type is the action's type.
nlohmann::json feedbackJson(std::string_view type, const realtime::ActionGoal& goal);
nlohmann::json resultJson(std::string_view type, const realtime::ActionGoal& goal);

}  // namespace servoloop::node
