#pragma once
// The Bullet engine behind the "bullet" backend: a BulletWorld (joint-space
// Featherstone physics from the URDF) driven through SimRobotHW's
// PhysicsEngine interface, with the same parameter semantics as the mujoco
// backend:
//  - effort commands are applied for one step as SimRobotHW sends them
//    (SimRobotHW has applied the URDF/YAML joint limits and the motor limits;
//    BulletWorld does not clamp a second time);
//  - velocity and position commands go to BulletWorld's joint motors, bounded
//    by EngineJointConfig::motor_effort_limit (the smaller of the joint effort
//    limit and Σ|ratio|·max_effort of its actuators);
//  - jointEffort() is the effort applied during the last step: the command in
//    effort mode, the motor's effort (impulse / time step) in motor modes;
//  - rotor inertia: the reflected n²·J is added to the child body's inertia
//    about the joint axis. Exact for the joint itself; a joint up the chain
//    with a non-perpendicular axis feels (a_i·a_j)·n²·J of it as well, which
//    true armature (mujoco) does not have — see docs/simulation.md. Prismatic
//    joints: not modelled (a warning is logged at init).
#include <memory>
#include <vector>

#include "servoloop/sim_bullet/bullet_scene.hpp"
#include "servoloop/sim_bullet/bullet_world.hpp"
#include "servoloop/sim_common/physics_engine.hpp"

namespace servoloop::sim_bullet {

class BulletPhysics final : public sim_common::PhysicsEngine {
 public:
  const char* name() const noexcept override { return "bullet"; }

  // A "bullet/world" (BulletSimulatedWorld): init() builds the robot into
  // its scene, beside the other robots; any other world must simulate its
  // robots apart (the robot then has a scene of its own).
  void joinWorld(hardware_interface::SimulatedWorld& world) override;

  void init(const urdf::ModelInterface& model, const sim_common::SimSettings& settings,
            const std::vector<sim_common::EngineJointConfig>& joints,
            const std::string& source_name) override;

  double jointPosition(std::size_t joint) const noexcept override;
  bool readBaseState(sim_common::EngineBaseState& out) const noexcept override;
  void setBaseState(const sim_common::EngineBaseState& state) override;
  double jointVelocity(std::size_t joint) const noexcept override;
  // The effort applied during the last step: the effort command in effort
  // mode, the motor's effort in velocity/position mode.
  double jointEffort(std::size_t joint) const noexcept override;

  void setJointEffort(std::size_t joint, double effort) noexcept override;
  void setJointVelocityTarget(std::size_t joint, double velocity) noexcept override;
  void setJointPositionTarget(std::size_t joint, double position) noexcept override;
  // All joints in one call each (what SimRobotHW uses every cycle).
  void readJointStates(std::span<sim_common::EngineJointState> states) const noexcept override;
  void applyJointCommands(std::span<const sim_common::AppliedJointCommand> commands) noexcept override;
  void step() noexcept override;

  // Sensors: any URDF link's frame; the wrench of a movable joint (a fixed
  // joint's links are one body in Bullet: ConfigError).
  bool simulatesSensors() const noexcept override { return true; }
  std::size_t trackLink(const std::string& link) override;
  void readLinkState(std::size_t tracked, sim_common::EngineLinkState& out) const noexcept override;
  std::size_t trackJointWrench(const std::string& joint) override;
  void readJointWrench(std::size_t tracked, sim_common::EngineJointWrench& out) const noexcept override;
  std::size_t trackContacts(const std::string& link) override;
  std::size_t readContacts(std::size_t tracked, std::span<sim_common::EngineContact> out) const noexcept override;

  void reset() override;
  void setJointState(std::size_t joint, double position, double velocity) override;

  // The world, for tests and diagnostics (null before init()).
  const BulletWorld* world() const { return world_.get(); }

 private:
  void placeAtInitialPositions();
  void applyMotorEffortLimits();

  BulletScene* shared_scene_ = nullptr;  // joinWorld's; null: a scene of the robot's own
  std::unique_ptr<BulletWorld> world_;
  std::vector<std::size_t> world_index_;         // SimRobotHW joint → BulletWorld joint
  std::vector<double> initial_positions_;
  std::vector<double> motor_effort_limits_;      // per SimRobotHW joint, N·m or N (+inf: none)
  mutable std::vector<LinkContact> contacts_;    // readContacts' scratch, sized by trackContacts
};

}  // namespace servoloop::sim_bullet
