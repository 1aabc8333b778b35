#include "servoloop/controllers/minimal_joint_controller/minimal_joint_controller.hpp"

#include <string>

#include "servoloop/plugin/plugin_register.hpp"
#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/controllers/common/angles.hpp"
#include "servoloop/controllers/common/controller_params.hpp"
#include "servoloop/controllers/common/joint_handles.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::controllers {

namespace cm = controller_manager;

bool MinimalJointController::init(hardware_interface::EffortJointInterface* hw,
                                  const cm::ControllerContext& context) {
  const std::string joint_name = optionalString(context, "joint", kDefaultJoint);
  kp_ = optionalNumber(context, "kp", kDefaultKp);
  kv_ = optionalNumber(context, "kv", kDefaultKv);
  const double update_rate_hz = optionalNumber(context, "update_rate", kDefaultUpdateRateHz);
  if (!(update_rate_hz > 0.0)) {
    throw ConfigError("controller '" + context.name + "': parameter '" +
                      parameterPath(context, "update_rate") + "' must be > 0 Hz (the seed used 100)");
  }
  gate_.setRate(update_rate_hz);
  joint_ = getJointHandle(*hw, joint_name, context, "joint");

  command_input_.connect(context.topics, controllerTopic(context, "pos_cmd"), context.name);
  if (context.topics != nullptr) {
    servoloop::realtime::TopicBus& topics = *context.topics;
    position_publisher_ = topics.advertise<Float64>(controllerTopic(context, "jnt_pos"));
    velocity_publisher_ = topics.advertise<Float64>(controllerTopic(context, "jnt_vel"));
    effort_publisher_ = topics.advertise<Float64>(controllerTopic(context, "jnt_trq"));
    // As the seed's node: one joint, position and velocity only.
    servoloop::sensor_msgs::JointState joint_state;
    joint_state.name = {joint_name};
    joint_state.position = {0.0};
    joint_state.velocity = {0.0};
    joint_state_publisher_ = topics.advertise<servoloop::sensor_msgs::JointState>(
        namespaceTopic(context, "joint_states"), joint_state);
    joint_state_publisher_.msg() = joint_state;
  }
  return true;
}

void MinimalJointController::starting(const Time& /*time*/) {
  position_command_ = 0.0;
  effort_ = 0.0;
  command_input_.clear();
  gate_.reset();
}

ReturnType MinimalJointController::update(const Time& time, const Duration& period) {
  if (gate_.due(time, period)) {
    ++control_updates_;
    command_input_.takeNew(position_command_);
    const double position = joint_.getPosition();
    const double velocity = joint_.getVelocity();
    effort_ = kp_ * wrapToPi(position_command_ - position) - kv_ * velocity;

    position_publisher_.publish(Float64{position});
    velocity_publisher_.publish(Float64{velocity});
    if (joint_state_publisher_.valid() && joint_state_publisher_.trylock()) {
      auto& msg = joint_state_publisher_.msg();
      msg.stamp = time.seconds;
      msg.position[0] = position;
      msg.velocity[0] = velocity;
      joint_state_publisher_.unlockAndPublish();
    }
    effort_publisher_.publish(Float64{effort_});
  }
  // Written every cycle, so the effort holds between control updates.
  joint_.setCommand(effort_);
  return ReturnType::ok;
}

}  // namespace servoloop::controllers

SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::MinimalJointController,
                          servoloop::controller_manager::ControllerBase,
                          "minimal_joint_controller/MinimalJointController")
