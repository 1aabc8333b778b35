#pragma once
// The Bullet engine behind the "bullet" backend: a BulletWorld (joint-space
// Featherstone physics from the URDF) driven through SimRobotHW's
// PhysicsEngine interface. Effort commands are applied for one step; velocity
// and position commands go to BulletWorld's joint motors, which the URDF
// <limit effort> bounds.
//
// Not modelled yet (each logged as a warning at init when it matters):
//  - rotor inertia (<ns>/actuators/<name>/rotor_inertia): adding n²·J needs
//    either a modified link inertia (wrong for the parent joints) or an
//    -n²·J·q̈ effort from the previous step's acceleration (unstable once n²·J
//    exceeds the link's own inertia). TODO: add it inside BulletWorld as a
//    joint-space armature term;
//  - a motor effort bound tighter than the URDF <limit effort> (from
//    actuators/<name>/max_effort or joint_limits/<joint>/max_effort) in velocity
//    and position modes: BulletWorld's motors take the URDF limit. Effort mode
//    honours every limit (SimRobotHW applies them before the engine);
//  - the effort of the velocity/position motors: jointEffort() reports 0 in
//    those modes, as BulletWorld does not expose the motor's impulse.
#include <memory>
#include <vector>

#include "servoloop/sim_bullet/bullet_world.hpp"
#include "servoloop/sim_common/physics_engine.hpp"

namespace servoloop::sim_bullet {

class BulletPhysics final : public sim_common::PhysicsEngine {
 public:
  const char* name() const noexcept override { return "bullet"; }

  void init(const urdf::ModelInterface& model, const sim_common::SimSettings& settings,
            const std::vector<sim_common::EngineJointConfig>& joints,
            const std::string& source_name) override;

  double jointPosition(std::size_t joint) const noexcept override;
  double jointVelocity(std::size_t joint) const noexcept override;
  // Effort mode: the effort applied during the last step (after BulletWorld's
  // clamp to the URDF effort limit). Motor modes: 0 (see above).
  double jointEffort(std::size_t joint) const noexcept override { return applied_efforts_[joint]; }

  void setJointEffort(std::size_t joint, double effort) noexcept override;
  void setJointVelocityTarget(std::size_t joint, double velocity) noexcept override;
  void setJointPositionTarget(std::size_t joint, double position) noexcept override;
  void step() noexcept override;

  void reset() override;
  void setJointState(std::size_t joint, double position, double velocity) override;

  // The world, for tests and diagnostics (null before init()).
  const BulletWorld* world() const { return world_.get(); }

 private:
  void placeAtInitialPositions();

  std::unique_ptr<BulletWorld> world_;
  std::vector<std::size_t> world_index_;         // SimRobotHW joint → BulletWorld joint
  std::vector<double> initial_positions_;
  std::vector<double> pending_efforts_;          // effort for the next step (0 in motor modes)
  std::vector<double> applied_efforts_;          // effort applied during the last step
};

}  // namespace servoloop::sim_bullet
