#pragma once
// MuJoCo stepped by hand, for the backend benchmark: the same hand-written
// law as RawBulletPd (HandWrittenPositionLaw, loop_fixtures.hpp) on
// servoloop's MuJoCo engine used directly — MujocoPhysics::setJointEffort → step() (which puts
// the effort in qfrc_applied and calls mj_step once, RK4) → jointPosition /
// jointVelocity. No SimRobotHW, transmissions, limits or controllers.
// Construction is set-up (allocates, throws); step() is what is timed.
#include <memory>
#include <vector>

#include <urdf_model/model.h>

#include "loop_fixtures.hpp"
#include "servoloop/sim_mujoco/mujoco_physics.hpp"

namespace servoloop::bench {

class RawMujocoPd {
 public:
  // The robot's URDF with default simulation settings (1 ms step, gravity −z,
  // no ground plane: what the robot YAMLs give), every controlled joint at 0,
  // at rest; the law's gains from the robot's controller YAML.
  explicit RawMujocoPd(const RobotCase& robot);
  // Real-time: the law's effort for every joint, then one physics step.
  void step() noexcept;
  // One physics step with no effort, as the servoloop loop's first cycle.
  void stepWithoutControl() noexcept;
  double jointPosition(std::size_t controlled_joint) const;
  // Largest |q| over the controlled joints (rad): shows a robot that went unstable.
  double maxAbsJointPosition() const;

 private:
  std::shared_ptr<const urdf::ModelInterface> model_;
  sim_mujoco::MujocoPhysics physics_;
  std::vector<HandWrittenPositionLaw> joints_;  // in the engine's joint order
};

}  // namespace servoloop::bench
