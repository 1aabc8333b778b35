#pragma once
// effort_controllers' forward-command types: the commanded joint effort
// (N·m or N) is written unchanged every cycle; commands start at 0.
//   effort_controllers/JointEffortController       param joint,  std_msgs/Float64
//   effort_controllers/JointGroupEffortController  param joints, std_msgs/Float64MultiArray
// Topic: <robot ns>/<controller>/command. See forward_command_controller.hpp.
#include "servoloop/controllers/common/forward_command_controller.hpp"
#include "servoloop/controllers/common/forward_joint_group_command_controller.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"

namespace servoloop::controllers::effort_controllers {

using JointEffortController = ForwardCommandController<hardware_interface::EffortJointInterface>;
using JointGroupEffortController =
    ForwardJointGroupCommandController<hardware_interface::EffortJointInterface>;

}  // namespace servoloop::controllers::effort_controllers
