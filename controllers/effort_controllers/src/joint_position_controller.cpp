#include "servoloop/controllers/effort_controllers/joint_position_controller.hpp"

#include <cmath>
#include <string>

#include "servoloop/plugin/plugin_register.hpp"
#include "servoloop/controllers/common/controller_params.hpp"
#include "servoloop/controllers/common/joint_handles.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::controllers::effort_controllers {

namespace cm = controller_manager;

bool JointPositionController::init(hardware_interface::EffortJointInterface* hw,
                                   const cm::ControllerContext& context) {
  const std::string joint_name = requireString(context, "joint", "joint: joint1");
  pid_.initFromParams(context.params.child("pid"), parameterPath(context, "pid"));
  if (context.robot_model) {
    position_error_ = JointPositionError::fromModel(*context.robot_model, joint_name, context.name);
  } else {
    logger().warn("controller '{}': no robot description was given, so joint '{}' is driven "
                  "without position limits and without angle wrapping (error = setpoint - position)",
                  context.name, joint_name);
  }
  joint_ = getJointHandle(*hw, joint_name, context, "joint");
  command_input_.connect(context.topics, controllerTopic(context, "command"), context.name);
  state_publisher_.advertise(context.topics, controllerTopic(context, "state"));
  return true;
}

void JointPositionController::setCommand(double position) {
  if (!std::isfinite(position)) return;
  direct_command_.writeFromNonRT(Command{position, 0.0, false});
}

void JointPositionController::setCommand(double position, double velocity) {
  if (!std::isfinite(position) || !std::isfinite(velocity)) return;
  direct_command_.writeFromNonRT(Command{position, velocity, true});
}

void JointPositionController::starting(const Time& /*time*/) {
  setpoint_ = position_error_.clampSetpoint(joint_.getPosition());
  has_velocity_target_ = false;
  velocity_target_ = 0.0;
  effort_ = 0.0;
  command_input_.clear();
  direct_command_.clearFromRT();
  pid_.reset();
  state_publisher_.reset();
}

ReturnType JointPositionController::update(const Time& time, const Duration& period) {
  // The every-cycle part is kept short; new setpoints and the state message
  // (every 10th update) are handled out of line.
  if (command_input_.hasNew() || direct_command_.newDataAvailable()) [[unlikely]] takeNewSetpoint();

  const double position = joint_.getPosition();
  const double velocity = joint_.getVelocity();
  const double error = position_error_.error(setpoint_, position);
  const double dt = period.seconds;
  effort_ = has_velocity_target_ ? pid_.computeCommand(error, velocity_target_ - velocity, dt)
                                 : pid_.computeCommand(error, dt);
  joint_.setCommand(effort_);

  if (state_publisher_.countUpdate()) publishState(time, position, velocity, error, dt);
  return ReturnType::ok;
}

void JointPositionController::takeNewSetpoint() noexcept {
  // The topic's, then a direct one (which wins if both came).
  double commanded_position = 0.0;
  if (command_input_.takeNew(commanded_position)) {
    setpoint_ = position_error_.clampSetpoint(commanded_position);
    has_velocity_target_ = false;
  }
  if (direct_command_.newDataAvailable()) {
    if (const Command* command = direct_command_.readFromRT()) {
      setpoint_ = position_error_.clampSetpoint(command->position);
      velocity_target_ = command->velocity;
      has_velocity_target_ = command->has_velocity;
    }
  }
}

void JointPositionController::publishState(const Time& time, double position, double velocity, double error,
                                           double dt) noexcept {
  state_publisher_.publish([&](ControllerStatePublisher::Message& msg) {
    msg.stamp = time.seconds;
    msg.set_point = setpoint_;
    msg.process_value = position;
    msg.process_value_dot = velocity;
    msg.error = error;
    msg.time_step = dt;
    msg.command = effort_;
    ControllerStatePublisher::setGains(msg, pid_.getActiveGains());
  });
}

}  // namespace servoloop::controllers::effort_controllers

SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::effort_controllers::JointPositionController,
                          servoloop::controller_manager::ControllerBase,
                          "effort_controllers/JointPositionController")
