#pragma once
// The two ways the loop benchmarks drive a simulated robot: raw Bullet with a
// PD written inline, and the whole servoloop loop on a robot_hw backend
// plugin. Construction is set-up (allocates, loads plugins, throws); the
// stepping calls are what the benchmarks time.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <urdf_model/model.h>
#include <yaml-cpp/yaml.h>

#include "servoloop/controller_manager/controller_manager.hpp"
#include "servoloop/controller_manager/plugin_loader.hpp"
#include "servoloop/controller_manager/simulation_loop.hpp"
#include "servoloop/controller_manager/topic_bus.hpp"
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

// (a) BulletWorld stepped by hand, with the control law of the robot's
// position controllers written inline: per joint, with e = q_ref − q,
//   effort = p·e + clamp(i·∫e dt, i_clamp_min, i_clamp_max) + d·(e − e_prev)/dt,
// saturated as ros_control's effort saturation does it (to ± the URDF effort
// limit, with the bound on the side that pushes further out set to 0 beyond a
// position limit or the velocity limit), → setJointEffort → step(); p, i, d
// and i_clamp from the robot's YAML. Running the same law and limits as the
// servoloop controllers keeps both runs on the same trajectory, so Bullet
// does the same work in both and the ratio shows the framework's cost alone.
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
    double setpoint_rad;
    double kp;
    double ki;
    double kd;
    double i_min;
    double i_max;
    double effort_limit;  // N·m; +infinity without one
    double lower;         // position limits (rad); ±infinity without
    double upper;
    double velocity_limit;  // rad/s; +infinity without one
    double error_before = 0.0;
    double error_integral = 0.0;
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
  controller_manager::PluginLoader loader_;  // declared first: outlives the objects it made
  controller_manager::TopicBus bus_;
  controller_manager::PluginPtr<hardware_interface::RobotHW> hw_;
  std::unique_ptr<controller_manager::ControllerManager> manager_;
  std::unique_ptr<controller_manager::SimulationLoop> loop_;
  hardware_interface::JointStateHandle first_joint_;
};

}  // namespace servoloop::bench
