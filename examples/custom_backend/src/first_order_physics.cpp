#include "my_backends/first_order_physics.hpp"

#include <algorithm>
#include <cmath>

namespace my_backends {

void FirstOrderPhysics::init(const urdf::ModelInterface& /*model*/,
                             const servoloop::sim_common::SimSettings& settings,
                             const std::vector<servoloop::sim_common::EngineJointConfig>& joints,
                             const std::string& /*source_name*/) {
  // SimRobotHW has already checked the URDF, that every joint of `joints` is a
  // movable joint, and the time step; FirstOrderRobotHW checked the parameters.
  time_step_s_ = settings.time_step_s;
  decay_ = std::exp(-time_step_s_ / parameters_.time_constant_s);
  joints_.assign(joints.size(), Joint{});
  for (std::size_t j = 0; j < joints.size(); ++j) {
    joints_[j].initial_position = joints[j].initial_position;
    // A motor that can give at most F against the damping b holds at most F / b.
    joints_[j].max_velocity_target = joints[j].motor_effort_limit / parameters_.damping;
  }
  reset();
}

void FirstOrderPhysics::setJointEffort(std::size_t joint, double effort) noexcept {
  joints_[joint].mode = Mode::effort;
  joints_[joint].command = effort;
}

void FirstOrderPhysics::setJointVelocityTarget(std::size_t joint, double velocity) noexcept {
  joints_[joint].mode = Mode::velocity;
  joints_[joint].command = velocity;
}

void FirstOrderPhysics::setJointPositionTarget(std::size_t joint, double position) noexcept {
  joints_[joint].mode = Mode::position;
  joints_[joint].command = position;
}

void FirstOrderPhysics::step() noexcept {
  const double dt = time_step_s_;
  const double tau = parameters_.time_constant_s;
  const double a = decay_;
  for (Joint& joint : joints_) {
    if (joint.mode == Mode::position) {
      const double target = joint.command;
      joint.position = target + (joint.position - target) * a;
      joint.velocity = (target - joint.position) / tau;
      joint.effort = 0.0;
      continue;
    }
    double velocity_target = 0.0;
    if (joint.mode == Mode::effort) {
      velocity_target = joint.command / parameters_.damping;
      joint.effort = joint.command;
      joint.command = 0.0;  // an effort acts for one step only
    } else {
      velocity_target = std::clamp(joint.command, -joint.max_velocity_target, joint.max_velocity_target);
      joint.effort = 0.0;
    }
    // Exact solution over [t, t + dt]: v(t) = v* + (v0 − v*)·e^(−t/τ), and its integral.
    const double excess = joint.velocity - velocity_target;
    joint.position += velocity_target * dt + excess * tau * (1.0 - a);
    joint.velocity = velocity_target + excess * a;
  }
}

void FirstOrderPhysics::reset() {
  for (Joint& joint : joints_) {
    joint.position = joint.initial_position;
    joint.velocity = 0.0;
    joint.effort = 0.0;
    joint.mode = Mode::effort;
    joint.command = 0.0;
  }
}

void FirstOrderPhysics::setJointState(std::size_t joint, double position, double velocity) {
  joints_.at(joint).position = position;
  joints_.at(joint).velocity = velocity;
}

}  // namespace my_backends
