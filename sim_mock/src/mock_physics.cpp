#include "mock_physics.hpp"

#include "servoloop/sim_common/joint_axis_inertia.hpp"

namespace servoloop::sim_mock {

using sim_common::JointCommandMode;

void MockPhysics::init(const urdf::ModelInterface& model, const sim_common::SimSettings& settings,
                       const std::vector<sim_common::EngineJointConfig>& joints,
                       const std::string& /*source_name*/) {
  time_step_s_ = settings.time_step_s;
  joints_.assign(joints.size(), Joint{});
  for (std::size_t j = 0; j < joints.size(); ++j) {
    joints_[j].inertia = sim_common::jointAxisInertia(model, joints[j].name) + joints[j].reflected_rotor_inertia;
    joints_[j].initial_position = joints[j].initial_position;
  }
  reset();
}

void MockPhysics::setJointEffort(std::size_t joint, double effort) noexcept {
  joints_[joint].mode = JointCommandMode::effort;
  joints_[joint].command = effort;
}

void MockPhysics::setJointVelocityTarget(std::size_t joint, double velocity) noexcept {
  joints_[joint].mode = JointCommandMode::velocity;
  joints_[joint].command = velocity;
}

void MockPhysics::setJointPositionTarget(std::size_t joint, double position) noexcept {
  joints_[joint].mode = JointCommandMode::position;
  joints_[joint].command = position;
}

void MockPhysics::step() noexcept {
  const double dt = time_step_s_;
  for (Joint& joint : joints_) {
    const double previous_velocity = joint.velocity;
    switch (joint.mode) {
      case JointCommandMode::none:
      case JointCommandMode::effort:
        joint.velocity += joint.command / joint.inertia * dt;
        joint.position += joint.velocity * dt;
        joint.effort = joint.command;
        joint.command = 0.0;  // an effort acts for one step
        continue;
      case JointCommandMode::velocity:
        joint.velocity = joint.command;
        joint.position += joint.velocity * dt;
        break;
      case JointCommandMode::position:
        joint.velocity = (joint.command - joint.position) / dt;
        joint.position = joint.command;
        break;
    }
    joint.effort = joint.inertia * (joint.velocity - previous_velocity) / dt;
  }
}

void MockPhysics::reset() {
  for (Joint& joint : joints_) {
    joint.position = joint.initial_position;
    joint.velocity = 0.0;
    joint.effort = 0.0;
    joint.mode = JointCommandMode::none;
    joint.command = 0.0;
  }
}

void MockPhysics::setJointState(std::size_t joint, double position, double velocity) {
  joints_.at(joint).position = position;
  joints_.at(joint).velocity = velocity;
}

}  // namespace servoloop::sim_mock
