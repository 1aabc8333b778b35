#include "servoloop/controllers/effort_controllers/joint_group_position_controller.hpp"

#include <string>

#include "servoloop/plugin/plugin_register.hpp"
#include "servoloop/controllers/common/controller_params.hpp"
#include "servoloop/controllers/common/joint_handles.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::controllers::effort_controllers {

namespace cm = controller_manager;

bool JointGroupPositionController::init(hardware_interface::EffortJointInterface* hw,
                                        const cm::ControllerContext& context) {
  const std::vector<std::string> joint_names =
      requireStringList(context, "joints", "joints: [joint1, joint2]");
  const std::size_t count = joint_names.size();
  pids_ = std::make_unique<Pid[]>(count);
  tunable_pids_.clear();
  position_errors_.assign(count, JointPositionError());
  for (std::size_t i = 0; i < count; ++i) {
    const std::string& joint_name = joint_names[i];
    pids_[i].initFromParams(context.params.child(joint_name).child("pid"),
                            parameterPath(context, joint_name + "/pid"));
    tunable_pids_.push_back({joint_name + "/pid", &pids_[i]});
    if (context.robot_model) {
      position_errors_[i] = JointPositionError::fromModel(*context.robot_model, joint_name, context.name);
    }
  }
  if (!context.robot_model) {
    logger().warn("controller '{}': no robot description was given, so its joints are driven "
                  "without position limits and without angle wrapping (error = setpoint - position)",
                  context.name);
  }
  joints_ = getJointHandles(*hw, joint_names, context, "joints");
  setpoints_.assign(count, 0.0);
  efforts_.assign(count, 0.0);
  command_input_.connect(context.topics, controllerTopic(context, "command"), count, context.name);
  return true;
}

void JointGroupPositionController::starting(const Time& /*time*/) {
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    setpoints_[i] = position_errors_[i].clampSetpoint(joints_[i].getPosition());
    efforts_[i] = 0.0;
    pids_[i].reset();
  }
  command_input_.clear();
}

ReturnType JointGroupPositionController::update(const Time& /*time*/, const Duration& period) {
  command_input_.takeNew(setpoints_);  // untouched unless a valid command arrived
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    setpoints_[i] = position_errors_[i].clampSetpoint(setpoints_[i]);
    const double error = position_errors_[i].error(setpoints_[i], joints_[i].getPosition());
    efforts_[i] = pids_[i].computeCommand(error, period.seconds);
    joints_[i].setCommand(efforts_[i]);
  }
  return ReturnType::ok;
}

}  // namespace servoloop::controllers::effort_controllers

SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::effort_controllers::JointGroupPositionController,
                          servoloop::controller_manager::ControllerBase,
                          "effort_controllers/JointGroupPositionController")
