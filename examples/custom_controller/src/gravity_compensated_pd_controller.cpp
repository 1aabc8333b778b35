#include "my_controllers/gravity_compensated_pd_controller.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "servoloop/controllers/common/controller_params.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/plugin/plugin_register.hpp"
#include "servoloop/realtime/topic_bus.hpp"

namespace my_controllers {

namespace cm = servoloop::controller_manager;
namespace hi = servoloop::hardware_interface;
// Parameter reading with errors that name the controller, the full parameter
// path as the user finds it in the YAML, and the fix (installed with servoloop).
using servoloop::controllers::optionalNumber;
using servoloop::controllers::parameterPath;
using servoloop::controllers::requireNumber;
using servoloop::controllers::requireString;

bool GravityCompensatedPDController::init(hi::EffortJointInterface* hw, const cm::ControllerContext& context) {
  // Parameters first, so a bad YAML fails before anything is claimed.
  const std::string joint_name = requireString(context, "joint", "joint: joint1");
  kp_ = requireNumber(context, "kp", "kp: 20.0");
  kd_ = optionalNumber(context, "kd", 0.0);
  gravity_torque_ = optionalNumber(context, "gravity_torque", 0.0);
  upright_position_ = optionalNumber(context, "upright_position", 0.0);
  max_effort_ = optionalNumber(context, "max_effort", std::numeric_limits<double>::infinity());
  if (kp_ < 0.0 || kd_ < 0.0) {
    throw servoloop::ConfigError("controller '" + context.name + "': gains '" + parameterPath(context, "kp") +
                                 "' and '" + parameterPath(context, "kd") + "' must be >= 0");
  }
  if (!(max_effort_ > 0.0)) {
    throw servoloop::ConfigError("controller '" + context.name + "': parameter '" +
                                 parameterPath(context, "max_effort") + "' must be > 0 N·m");
  }

  // getHandle on a command interface claims the joint for this controller; an
  // unknown joint throws an error listing the joints the hardware has.
  joint_ = hw->getHandle(joint_name);

  // The command input is made here, off the real-time thread; update() only reads it.
  command_topic_ = servoloop::controllers::controllerTopic(context, "command");
  if (context.topics != nullptr) {
    command_ = context.topics->commandInput<servoloop::std_msgs::Float64>(command_topic_);
  }
  return true;
}

void GravityCompensatedPDController::starting(const servoloop::Time& /*time*/) {
  position_setpoint_ = joint_.getPosition();
  // A command published before this start is stale: wait for a new one.
  command_.clear();
}

servoloop::ReturnType GravityCompensatedPDController::update(const servoloop::Time& /*time*/,
                                                             const servoloop::Duration& /*period*/) {
  // Take the newest command, if one came; a non-finite one is ignored and the
  // previous setpoint stays.
  if (const servoloop::std_msgs::Float64* command = command_.latest()) {
    if (std::isfinite(command->data)) position_setpoint_ = command->data;
  }

  const double position = joint_.getPosition();
  const double velocity = joint_.getVelocity();
  const double pd_effort = kp_ * (position_setpoint_ - position) - kd_ * velocity;
  const double gravity_compensation = -gravity_torque_ * std::sin(position - upright_position_);
  // std::clamp keeps a NaN (a broken joint reading): the manager then sees a
  // non-finite command, stops this controller and writes a safe (zero) effort.
  joint_.setCommand(std::clamp(pd_effort + gravity_compensation, -max_effort_, max_effort_));
  return servoloop::ReturnType::ok;
}

void GravityCompensatedPDController::stopping(const servoloop::Time& /*time*/) {
  command_.clear();
}

}  // namespace my_controllers

// One line registers the class under the type name users write in their YAML
// (`type: my_controllers/GravityCompensatedPD`).
SERVOLOOP_REGISTER_PLUGIN(my_controllers::GravityCompensatedPDController,
                          servoloop::controller_manager::ControllerBase,
                          "my_controllers/GravityCompensatedPD")
