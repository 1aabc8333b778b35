#include "servoloop/controllers/effort_controllers/joint_velocity_controller.hpp"

#include <string>

#include "servoloop/plugin/plugin_register.hpp"
#include "servoloop/controllers/common/controller_params.hpp"
#include "servoloop/controllers/common/joint_handles.hpp"

namespace servoloop::controllers::effort_controllers {

namespace cm = controller_manager;

bool JointVelocityController::init(hardware_interface::EffortJointInterface* hw,
                                   const cm::ControllerContext& context) {
  const std::string joint_name = requireString(context, "joint", "joint: joint1");
  pid_.initFromParams(context.params.child("pid"), parameterPath(context, "pid"));
  joint_ = getJointHandle(*hw, joint_name, context, "joint");
  command_input_.connect(context.topics, controllerTopic(context, "command"), context.name);
  state_publisher_.advertise(context.topics, controllerTopic(context, "state"));
  return true;
}

void JointVelocityController::starting(const Time& /*time*/) {
  velocity_setpoint_ = 0.0;
  effort_ = 0.0;
  command_input_.clear();
  pid_.reset();
  state_publisher_.reset();
}

ReturnType JointVelocityController::update(const Time& time, const Duration& period) {
  command_input_.takeNew(velocity_setpoint_);
  const double velocity = joint_.getVelocity();
  const double error = velocity_setpoint_ - velocity;
  const double dt = period.seconds;
  effort_ = pid_.computeCommand(error, dt);
  joint_.setCommand(effort_);

  state_publisher_.onUpdate([&](ControllerStatePublisher::Message& msg) {
    msg.stamp = time.seconds;
    msg.set_point = velocity_setpoint_;
    msg.process_value = velocity;
    msg.process_value_dot = 0.0;
    msg.error = error;
    msg.time_step = dt;
    msg.command = effort_;
    ControllerStatePublisher::setGains(msg, pid_.getActiveGains());
  });
  return ReturnType::ok;
}

}  // namespace servoloop::controllers::effort_controllers

SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::effort_controllers::JointVelocityController,
                          servoloop::controller_manager::ControllerBase,
                          "effort_controllers/JointVelocityController")
