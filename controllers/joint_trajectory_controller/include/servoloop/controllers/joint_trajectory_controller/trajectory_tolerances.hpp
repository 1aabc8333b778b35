#pragma once
// How far a joint trajectory controller lets its joints stray from the
// trajectory, as ros_controllers' joint_trajectory_controller reads and
// applies them (the `constraints` parameters and a follow_joint_trajectory
// goal's own tolerances):
//   - path tolerance (constraints/<joint>/trajectory): |desired - actual|
//     position while the trajectory runs;
//   - goal tolerance (constraints/<joint>/goal, and
//     constraints/stopped_velocity_tolerance for the velocity): position and
//     velocity error once the last point's time has come;
//   - goal_time: how long after that the goal tolerance may still be met.
// A tolerance of 0 is not checked.
#include <string>
#include <vector>

#include "servoloop/controller_manager/controller_context.hpp"

namespace servoloop::controllers::joint_trajectory_controller {

// One joint's tolerance on its state error; 0 = not checked.
struct StateTolerance {
  double position = 0.0;      // rad or m
  double velocity = 0.0;      // rad/s or m/s
  double acceleration = 0.0;  // rad/s² or m/s²
};

// Real-time: whether every error is inside its (checked) tolerance.
inline bool withinTolerance(const StateTolerance& tolerance, double position_error, double velocity_error,
                            double acceleration_error) noexcept {
  const auto inside = [](double limit, double error) { return !(limit > 0.0) || !(error > limit || -error > limit); };
  return inside(tolerance.position, position_error) && inside(tolerance.velocity, velocity_error) &&
         inside(tolerance.acceleration, acceleration_error);
}

struct TrajectoryTolerances {
  std::vector<StateTolerance> path;  // one per joint
  std::vector<StateTolerance> goal;  // one per joint
  double goal_time = 0.0;            // s
};

// ros_controllers' defaults.
inline constexpr double kDefaultStoppedVelocityTolerance = 0.01;

// Non-real-time. The `constraints` map of a controller's parameters, for
// joint_names in order. Throws servoloop::ConfigError naming the parameter
// for a value that is not a number or is negative, or a joint key that is
// not one of the controller's joints.
TrajectoryTolerances readTolerances(const controller_manager::ControllerContext& context,
                                    const std::vector<std::string>& joint_names);

// A tolerance a goal gives for one joint (control_msgs/JointTolerance): for
// each value, > 0 replaces the default, 0 keeps it, < 0 turns the check off.
struct JointToleranceOverride {
  std::string name;
  double position = 0.0;
  double velocity = 0.0;
  double acceleration = 0.0;
};

// Non-real-time. defaults with a goal's path and goal tolerances and goal
// time tolerance (> 0 replaces, 0 keeps, < 0 turns off) applied. Throws
// servoloop::Error naming a joint the controller does not have.
TrajectoryTolerances applyGoalTolerances(const TrajectoryTolerances& defaults,
                                         const std::vector<std::string>& joint_names,
                                         const std::vector<JointToleranceOverride>& path,
                                         const std::vector<JointToleranceOverride>& goal, double goal_time);

}  // namespace servoloop::controllers::joint_trajectory_controller
