#pragma once
// FirstOrderPhysics: the physics of the "first_order" backend. Every joint is
// a first-order lag with time constant τ from its command to its motion:
//
//   velocity mode:       velocity follows the velocity target  v* = command
//   effort mode / none:  velocity follows                      v* = effort / damping
//                        (a joint in viscous oil: steady speed ∝ effort)
//   position mode:       position follows the position target  p* = command
//
//   τ · dv/dt = v* − v         (velocity and effort modes; dq/dt = v)
//   τ · dq/dt = p* − q         (position mode; v = dq/dt)
//
// Each step integrates these exactly over one time step dt (a = e^(−dt/τ)):
//
//   v ← v* + (v − v*)·a,   q ← q + v*·dt + (v − v*)·τ·(1 − a)
//   q ← p* + (q − p*)·a,   v ← (p* − q)/τ
//
// so the joint state after n steps is the analytic solution at t = n·dt, for
// any dt. In velocity mode |v*| is bounded by the joint's motor effort limit
// divided by the damping (the speed a motor of that strength holds against
// the damping). No gravity, contacts, coupling between joints or position
// stops; rotor inertia is not modelled (the model has no inertia).
//
// Threading, as PhysicsEngine requires: configure(), init(), reset() and
// setJointState() are non-real-time; everything else runs on the real-time
// thread and only reads and writes the preallocated joint table.
#include <cstddef>
#include <string>
#include <vector>

#include "servoloop/sim_common/physics_engine.hpp"

namespace my_backends {

// The backend's own parameters, <robot ns>/first_order/ in the parameter YAML.
struct FirstOrderParameters {
  double time_constant_s = 0.05;  // τ, s, > 0
  double damping = 1.0;           // N·m·s/rad (N·s/m for prismatic joints), > 0
};

class FirstOrderPhysics final : public servoloop::sim_common::PhysicsEngine {
 public:
  // Non-real-time. Takes effect at the next init() (call it before).
  void configure(const FirstOrderParameters& parameters) { parameters_ = parameters; }
  const FirstOrderParameters& parameters() const noexcept { return parameters_; }

  const char* name() const noexcept override { return "first_order"; }

  // Non-real-time. Sizes the joint table once; nothing on the real-time path
  // allocates afterwards.
  void init(const urdf::ModelInterface& model, const servoloop::sim_common::SimSettings& settings,
            const std::vector<servoloop::sim_common::EngineJointConfig>& joints,
            const std::string& source_name) override;

  double jointPosition(std::size_t joint) const noexcept override { return joints_[joint].position; }
  double jointVelocity(std::size_t joint) const noexcept override { return joints_[joint].velocity; }
  // Effort mode (and none): the effort applied during the last step. Velocity
  // and position modes: 0 (as the bullet backend reports them).
  double jointEffort(std::size_t joint) const noexcept override { return joints_[joint].effort; }

  void setJointEffort(std::size_t joint, double effort) noexcept override;
  void setJointVelocityTarget(std::size_t joint, double velocity) noexcept override;
  void setJointPositionTarget(std::size_t joint, double position) noexcept override;

  void step() noexcept override;

  void reset() override;
  void setJointState(std::size_t joint, double position, double velocity) override;

 private:
  enum class Mode { effort, velocity, position };

  struct Joint {
    double initial_position = 0.0;
    double max_velocity_target = 0.0;  // motor effort limit / damping (may be +inf)
    double position = 0.0;
    double velocity = 0.0;
    double effort = 0.0;
    Mode mode = Mode::effort;
    double command = 0.0;  // effort, velocity target or position target, by mode
  };

  FirstOrderParameters parameters_;
  double time_step_s_ = 0.001;
  double decay_ = 0.0;  // a = e^(−dt/τ), computed once in init()
  std::vector<Joint> joints_;
};

}  // namespace my_backends
