#pragma once
// Ideal actuators without a physics engine, like ros2_control's generic mock
// system: a position command is reached in one step, a velocity command is
// integrated, an effort command accelerates the joint by effort / inertia
// (the joint's inertia about its axis from the URDF plus the reflected rotor
// inertia). No gravity, no contacts, no damping or friction, no coupling
// between joints, no position stops (joint limits act on the commands).
#include <vector>

#include "servoloop/sim_common/stored_command_physics_engine.hpp"

namespace servoloop::sim_mock {

class MockPhysics final : public sim_common::StoredCommandPhysicsEngine {
 public:
  const char* name() const noexcept override { return "mock"; }

  void init(const urdf::ModelInterface& model, const sim_common::SimSettings& settings,
            const std::vector<sim_common::EngineJointConfig>& joints,
            const std::string& source_name) override;

  double jointPosition(std::size_t joint) const noexcept override { return joints_[joint].position; }
  double jointVelocity(std::size_t joint) const noexcept override { return joints_[joint].velocity; }
  // Effort mode: the effort applied. Motor modes: the effort an ideal motor
  // needed for the step's velocity change, inertia · Δvelocity / time step.
  double jointEffort(std::size_t joint) const noexcept override { return joints_[joint].effort; }

  // Semi-implicit Euler: velocity first, then position with the new velocity.
  void step() noexcept override;

  void reset() override;
  void setJointState(std::size_t joint, double position, double velocity) override;

  // Inertia the effort mode divides by (kg·m² or kg), for tests.
  double jointInertia(std::size_t joint) const { return joints_.at(joint).inertia; }

 private:
  struct Joint {
    double inertia = 1.0;  // link subtree about the axis + reflected rotor inertia
    double initial_position = 0.0;
    double position = 0.0;
    double velocity = 0.0;
    double effort = 0.0;
  };

  std::vector<Joint> joints_;
  double time_step_s_ = 0.001;
};

}  // namespace servoloop::sim_mock
