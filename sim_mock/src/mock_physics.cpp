#include "mock_physics.hpp"

#include "servoloop/sim_common/joint_axis_inertia.hpp"

namespace servoloop::sim_mock {

using sim_common::JointCommandMode;

void MockPhysics::init(const urdf::ModelInterface& model, const sim_common::SimSettings& settings,
                       const std::vector<sim_common::EngineJointConfig>& joints,
                       const std::string& /*source_name*/) {
  time_step_s_ = settings.time_step_s;
  joints_.assign(joints.size(), Joint{});
  resizeJointCommands(joints.size());
  for (std::size_t j = 0; j < joints.size(); ++j) {
    joints_[j].inertia = sim_common::jointAxisInertia(model, joints[j].name) + joints[j].reflected_rotor_inertia;
    joints_[j].initial_position = joints[j].initial_position;
  }
  reset();
}

void MockPhysics::step() noexcept {
  const double dt = time_step_s_;
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    Joint& joint = joints_[j];
    const sim_common::AppliedJointCommand& command = jointCommand(j);
    const double previous_velocity = joint.velocity;
    switch (command.mode) {
      case JointCommandMode::none:
      case JointCommandMode::effort:
        joint.velocity += command.value / joint.inertia * dt;
        joint.position += joint.velocity * dt;
        joint.effort = command.value;
        continue;
      case JointCommandMode::velocity:
        joint.velocity = command.value;
        joint.position += joint.velocity * dt;
        break;
      case JointCommandMode::position:
        joint.velocity = (command.value - joint.position) / dt;
        joint.position = command.value;
        break;
    }
    joint.effort = joint.inertia * (joint.velocity - previous_velocity) / dt;
  }
  endEffortCommands();
}

void MockPhysics::reset() {
  for (Joint& joint : joints_) {
    joint.position = joint.initial_position;
    joint.velocity = 0.0;
    joint.effort = 0.0;
  }
  clearJointCommands();
}

void MockPhysics::setJointState(std::size_t joint, double position, double velocity) {
  joints_.at(joint).position = position;
  joints_.at(joint).velocity = velocity;
}

}  // namespace servoloop::sim_mock
