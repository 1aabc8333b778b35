#include "servoloop/controllers/joint_trajectory_controller/trajectory_tolerances.hpp"

#include <algorithm>

#include "servoloop/controllers/common/controller_params.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::controllers::joint_trajectory_controller {
namespace {

double nonNegative(const controller_manager::ControllerContext& context, const params::Parameters& value,
                   const std::string& key, double fallback) {
  const std::string where = parameterPath(context, key);
  double number = 0.0;
  try {
    number = numberAt(value, where, fallback);
  } catch (const ConfigError& e) {
    throw ConfigError("controller '" + context.name + "': " + e.what());
  }
  if (number < 0.0) {
    throw ConfigError("controller '" + context.name + "': parameter '" + where + "' is " + std::to_string(number) +
                      "; a tolerance is >= 0 (0 = not checked)");
  }
  return number;
}

std::size_t indexOf(const std::vector<std::string>& names, const std::string& name) {
  return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
}

void applyOverride(double given, double& value) {
  if (given > 0.0) value = given;
  else if (given < 0.0) value = 0.0;
}

}  // namespace

TrajectoryTolerances readTolerances(const controller_manager::ControllerContext& context,
                                    const std::vector<std::string>& joint_names) {
  const params::Parameters constraints = context.params.child("constraints");
  TrajectoryTolerances tolerances;
  tolerances.path.assign(joint_names.size(), {});
  tolerances.goal.assign(joint_names.size(), {});
  if (!constraints.empty() && !constraints.isMap()) {
    throw ConfigError("controller '" + context.name + "': parameter '" + parameterPath(context, "constraints") +
                      "' must be a map, e.g. '{goal_time: 0.5, " + joint_names.front() + ": {goal: 0.01}}'");
  }
  tolerances.goal_time = nonNegative(context, constraints.child("goal_time"), "constraints/goal_time", 0.0);
  const double stopped_velocity = nonNegative(context, constraints.child("stopped_velocity_tolerance"),
                                              "constraints/stopped_velocity_tolerance",
                                              kDefaultStoppedVelocityTolerance);
  for (const std::string& key : constraints.keys()) {
    if (key == "goal_time" || key == "stopped_velocity_tolerance") continue;
    if (indexOf(joint_names, key) == joint_names.size()) {
      throw ConfigError("controller '" + context.name + "': parameter '" +
                        parameterPath(context, "constraints/" + key) + "' names no joint of the controller (" +
                        joinNames(joint_names) + "); constraints takes goal_time, stopped_velocity_tolerance "
                        "and one entry per joint");
    }
  }
  for (std::size_t j = 0; j < joint_names.size(); ++j) {
    const std::string key = "constraints/" + joint_names[j];
    const params::Parameters joint = constraints.child(joint_names[j]);
    tolerances.path[j].position = nonNegative(context, joint.child("trajectory"), key + "/trajectory", 0.0);
    tolerances.goal[j].position = nonNegative(context, joint.child("goal"), key + "/goal", 0.0);
    tolerances.goal[j].velocity = stopped_velocity;
  }
  return tolerances;
}

TrajectoryTolerances applyGoalTolerances(const TrajectoryTolerances& defaults,
                                         const std::vector<std::string>& joint_names,
                                         const std::vector<JointToleranceOverride>& path,
                                         const std::vector<JointToleranceOverride>& goal, double goal_time) {
  TrajectoryTolerances tolerances = defaults;
  const auto apply = [&](const std::vector<JointToleranceOverride>& overrides, std::vector<StateTolerance>& out,
                         const char* which) {
    for (const JointToleranceOverride& given : overrides) {
      const std::size_t j = indexOf(joint_names, given.name);
      if (j == joint_names.size()) {
        throw Error(std::string(which) + " names joint '" + given.name + "', which the controller does not have (" +
                    joinNames(joint_names) + ")");
      }
      applyOverride(given.position, out[j].position);
      applyOverride(given.velocity, out[j].velocity);
      applyOverride(given.acceleration, out[j].acceleration);
    }
  };
  apply(path, tolerances.path, "path_tolerance");
  apply(goal, tolerances.goal, "goal_tolerance");
  applyOverride(goal_time, tolerances.goal_time);
  return tolerances;
}

}  // namespace servoloop::controllers::joint_trajectory_controller
