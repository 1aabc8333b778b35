#include "servoloop/node/action_json.hpp"

#include <cmath>

#include "servoloop/core/errors.hpp"
#include "servoloop/node/message_json.hpp"

namespace servoloop::node {
namespace {

using nlohmann::json;
constexpr std::string_view kFollowJointTrajectory = control_msgs::FollowJointTrajectoryGoal::kActionType;
constexpr std::string_view kGripperCommand = control_msgs::GripperCommandGoal::kActionType;

[[noreturn]] void fail(const std::string& field, const std::string& problem,
                       std::string_view type = kFollowJointTrajectory) {
  throw Error(std::string(type) + " goal: field '" + field + "': " + problem);
}

double finiteNumber(const json& value, const std::string& field, std::string_view type = kFollowJointTrajectory) {
  if (!value.is_number()) fail(field, "expected a number, got " + value.dump(), type);
  const double number = value.get<double>();
  if (!std::isfinite(number)) fail(field, "must be a finite number", type);
  return number;
}

std::vector<control_msgs::JointTolerance> tolerances(const json& value, const std::string& field) {
  std::vector<control_msgs::JointTolerance> out;
  if (value.is_null()) return out;
  if (!value.is_array()) fail(field, "expected a list of {name, position, velocity, acceleration}");
  for (std::size_t i = 0; i < value.size(); ++i) {
    const std::string where = field + "[" + std::to_string(i) + "]";
    const json& item = value[i];
    if (!item.is_object()) fail(where, "expected an object {name, position, velocity, acceleration}");
    control_msgs::JointTolerance tolerance;
    for (const auto& [key, entry] : item.items()) {
      if (key == "name") {
        if (!entry.is_string()) fail(where + ".name", "expected a joint name");
        tolerance.name = entry.get<std::string>();
      } else if (key == "position") {
        tolerance.position = finiteNumber(entry, where + ".position");
      } else if (key == "velocity") {
        tolerance.velocity = finiteNumber(entry, where + ".velocity");
      } else if (key == "acceleration") {
        tolerance.acceleration = finiteNumber(entry, where + ".acceleration");
      } else {
        fail(where + "." + key, "unknown field; the fields are: name, position, velocity, acceleration");
      }
    }
    if (tolerance.name.empty()) fail(where + ".name", "missing: name the joint the tolerance is for");
    out.push_back(std::move(tolerance));
  }
  return out;
}

}  // namespace

std::vector<std::string> knownActionTypes() { return {std::string(kFollowJointTrajectory), std::string(kGripperCommand)}; }

void fromJson(const json& value, control_msgs::GripperCommandGoal& out) {
  if (!value.is_object()) {
    throw Error(std::string(kGripperCommand) + " goal: expected {command: {position, max_effort}}, got " + value.dump());
  }
  for (const auto& [key, entry] : value.items()) {
    if (key != "command") fail(key, "unknown field; the goal has one field, command: {position, max_effort}", kGripperCommand);
    if (!entry.is_object()) fail("command", "expected {position, max_effort}", kGripperCommand);
    for (const auto& [field, number] : entry.items()) {
      if (field == "position") {
        out.command.position = finiteNumber(number, "command.position", kGripperCommand);
      } else if (field == "max_effort") {
        out.command.max_effort = finiteNumber(number, "command.max_effort", kGripperCommand);
      } else {
        fail("command." + field, "unknown field; the fields are: position, max_effort", kGripperCommand);
      }
    }
  }
}

json toJson(const control_msgs::GripperCommandFeedback& feedback) {
  return json{{"position", feedback.position},
              {"effort", feedback.effort},
              {"stalled", feedback.stalled},
              {"reached_goal", feedback.reached_goal}};
}

void fromJson(const json& value, control_msgs::FollowJointTrajectoryGoal& out) {
  if (!value.is_object()) {
    throw Error(std::string(kFollowJointTrajectory) +
                " goal: expected an object with fields trajectory, path_tolerance, goal_tolerance, "
                "goal_time_tolerance, got " + value.dump());
  }
  for (const auto& [key, entry] : value.items()) {
    if (key == "trajectory") {
      try {
        out.trajectory = messageFromJson<trajectory_msgs::JointTrajectory>(entry);
        requireFiniteCommand(trajectory_msgs::JointTrajectory::kTypeName, toJson(out.trajectory));
      } catch (const Error& e) {
        fail("trajectory", e.what());
      }
    } else if (key == "path_tolerance") {
      out.path_tolerance = tolerances(entry, key);
    } else if (key == "goal_tolerance") {
      out.goal_tolerance = tolerances(entry, key);
    } else if (key == "goal_time_tolerance") {
      out.goal_time_tolerance = finiteNumber(entry, key);
    } else {
      fail(key, "unknown field; the fields are: trajectory, path_tolerance, goal_tolerance, goal_time_tolerance");
    }
  }
}

json toJson(const control_msgs::FollowJointTrajectoryFeedback& feedback) {
  control_msgs::JointTrajectoryControllerState state;
  state.stamp = feedback.stamp;
  state.joint_names = feedback.joint_names;
  state.desired = feedback.desired;
  state.actual = feedback.actual;
  state.error = feedback.error;
  return toJson(state);
}

json toJson(const control_msgs::FollowJointTrajectoryResult& result) {
  return json{{"error_code", result.error_code}, {"error_string", result.error_string}};
}

std::shared_ptr<realtime::ActionGoal> sendGoalJson(realtime::ActionRegistry& actions, std::string_view name,
                                                   std::string type, const json& goal) {
  if (type.empty()) type = actions.typeOf(name);
  if (type == kFollowJointTrajectory) {
    control_msgs::FollowJointTrajectoryGoal message;
    fromJson(goal, message);
    return actions.sendGoal(name, type, &message);
  }
  if (type == kGripperCommand) {
    control_msgs::GripperCommandGoal message;
    fromJson(goal, message);
    return actions.sendGoal(name, type, &message);
  }
  if (type.empty()) return actions.sendGoal(name, type, nullptr);  // names the actions there are
  std::string known;
  for (const std::string& t : knownActionTypes()) known += (known.empty() ? "" : ", ") + t;
  throw Error("unknown action type '" + type + "'; known types: " + known);
}

json feedbackJson(std::string_view type, const realtime::ActionGoal& goal) {
  if (type == kFollowJointTrajectory) {
    control_msgs::FollowJointTrajectoryFeedback feedback;
    if (!goal.feedback(&feedback)) return nullptr;
    return toJson(feedback);
  }
  if (type == kGripperCommand) {
    control_msgs::GripperCommandFeedback feedback;
    if (!goal.feedback(&feedback)) return nullptr;
    return toJson(feedback);
  }
  return nullptr;
}

json resultJson(std::string_view type, const realtime::ActionGoal& goal) {
  if (type == kFollowJointTrajectory) {
    control_msgs::FollowJointTrajectoryResult result;
    goal.result(&result);
    return toJson(result);
  }
  if (type == kGripperCommand) {
    control_msgs::GripperCommandResult result;
    goal.result(&result);
    return toJson(result);
  }
  return nullptr;
}

}  // namespace servoloop::node
