#pragma once
// The two ways the loop benchmarks drive a simulated robot: raw Bullet with a
// PD written inline, and the whole servoloop loop on a robot_hw backend
// plugin. Construction is set-up (allocates, loads plugins, throws); the
// stepping calls are what the benchmarks time.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <urdf_model/model.h>
#include <yaml-cpp/yaml.h>

#include "servoloop/controller_manager/controller_manager.hpp"
#include "servoloop/plugin/plugin_loader.hpp"
#include "servoloop/controller_manager/simulation_loop.hpp"
#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/hardware_interface/joint_state_handle.hpp"
#include "servoloop/hardware_interface/simulated_robot_hw.hpp"
#include "servoloop/sim_bullet/bullet_world.hpp"

namespace servoloop::bench {

inline constexpr double kTimeStepS = 0.001;
inline constexpr double kManagerRateHz = 1000.0;

// One robot set-up: files, controllers, setpoints, episode length.
struct RobotCase {
  std::string label;       // benchmark name part, e.g. "seed"
  std::string urdf;        // relative to the source tree
  std::string params;      // controller YAML, relative to the source tree
  std::string params_key;  // the robot namespace's key in that YAML, e.g. "one_DOF_robot"
  std::vector<std::string> position_controllers;  // one per joint (empty when a group controller is used)
  std::string group_controller;                   // the group controller (empty: per-joint)
  std::vector<std::string> joints;                // controlled joints, in setpoint order
  std::vector<double> setpoints_rad;
  std::uint64_t steps_per_episode = 0;

  std::string robotNamespace() const { return "/" + params_key; }
  YAML::Node namespaceParams() const;
};

// The seed's one_dof robot (second URDF, with transmission) and controller
// YAML; setpoint 1.0 rad; 10,000 steps.
RobotCase seedRobot();
// robots/chain32 with one JointPositionController per joint, or (group) one
// JointGroupPositionController; setpoints 0.2·sin(2π·i/16) rad; 2,000 steps.
RobotCase chainRobot(bool group);

// The control law of the robot's position controllers, written out by hand
// for the raw loops, per joint, with e = q_ref − q:
//   effort = p·e + clamp(i·∫e dt, i_clamp_min, i_clamp_max) + d·(e − e_prev)/dt,
// saturated as ros_control's effort saturation does it: to ± the URDF effort
// limit, with the bound on the side that pushes further out set to 0 beyond a
// position limit or the velocity limit. p, i, d and i_clamp come from the
// robot's YAML. Running the servoloop controllers' law and limits keeps the
// raw and servoloop runs on the same trajectory, so the engine does the same
// work in both and the ratio shows the framework's cost alone.
struct HandWrittenPositionLaw {
  double setpoint_rad = 0.0;
  double kp = 0.0, ki = 0.0, kd = 0.0;
  double i_min = 0.0, i_max = 0.0;
  double effort_limit = 0.0;    // N·m; +infinity without one
  double lower = 0.0, upper = 0.0;  // position limits (rad); ±infinity without
  double velocity_limit = 0.0;  // rad/s; +infinity without one
  double error_before = 0.0;
  double error_integral = 0.0;

  // Non-real-time: controlled joint i of `robot`, gains from `params` (its
  // namespace's parameters, RobotCase::namespaceParams()), limits from `model`.
  static HandWrittenPositionLaw forJoint(const RobotCase& robot, const YAML::Node& params, std::size_t i,
                                         const urdf::ModelInterface& model);

  // Real-time: the effort for this step.
  double effort(double position, double velocity) noexcept {
    const double error = setpoint_rad - position;
    const double error_rate = (error - error_before) / kTimeStepS;
    error_before = error;
    error_integral += kTimeStepS * error;
    const double i_term = std::min(std::max(ki * error_integral, i_min), i_max);
    const double unlimited = kp * error + i_term + kd * error_rate;
    double min_effort = -effort_limit;
    double max_effort = effort_limit;
    if (position < lower || velocity < -velocity_limit) min_effort = 0.0;
    if (position > upper || velocity > velocity_limit) max_effort = 0.0;
    return std::min(std::max(unlimited, min_effort), max_effort);
  }
};

// (a) BulletWorld stepped by hand with HandWrittenPositionLaw →
// setJointEffort → step().
class RawBulletPd {
 public:
  explicit RawBulletPd(const RobotCase& robot);
  // Real-time: one control computation and one physics step.
  void step() noexcept;
  // One physics step with no effort, as the servoloop loop's first cycle (in
  // which the controllers are started and command nothing yet).
  void stepWithoutControl() noexcept;
  double jointPosition(std::size_t controlled_joint) const;
  // Largest |q| over the controlled joints (rad): shows a robot that went unstable.
  double maxAbsJointPosition() const;

 private:
  struct Joint {
    std::size_t index;  // BulletWorld's joint index
    HandWrittenPositionLaw law;
  };
  std::shared_ptr<const urdf::ModelInterface> model_;
  std::unique_ptr<sim_bullet::BulletWorld> world_;
  std::vector<Joint> joints_;
};

// (b) SimulationLoop on a robot_hw plugin ("bullet", "mock") with the robot's
// JointStateController and position controller(s) loaded from the build's
// plugin folder, started (one loop cycle), commanded to the setpoints, and
// the topic bus's delivery thread running, as in a node.
class ServoloopSimulation {
 public:
  ServoloopSimulation(const RobotCase& robot, const std::string& backend);
  ~ServoloopSimulation();
  ServoloopSimulation(const ServoloopSimulation&) = delete;
  ServoloopSimulation& operator=(const ServoloopSimulation&) = delete;

  // Real-time loop: SimulationLoop::runFor(steps · dt), free-running.
  void runSteps(std::uint64_t steps);
  std::uint64_t stepsTaken() const { return loop_->stepsTaken(); }
  std::uint64_t hardwareErrors() const;
  double firstJointPosition() const { return first_joint_.getPosition(); }
  const controller_manager::SimulationLoop& loop() const { return *loop_; }

 private:
  servoloop::plugin::PluginLoader loader_;  // declared first: outlives the objects it made
  servoloop::realtime::TopicBus bus_;
  servoloop::plugin::PluginPtr<hardware_interface::RobotHW> hw_;
  std::unique_ptr<controller_manager::ControllerManager> manager_;
  std::unique_ptr<controller_manager::SimulationLoop> loop_;
  hardware_interface::JointStateHandle first_joint_;
};

}  // namespace servoloop::bench
