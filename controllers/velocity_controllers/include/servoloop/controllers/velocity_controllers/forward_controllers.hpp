#pragma once
// velocity_controllers' forward-command types: the commanded joint velocity (rad/s or m/s) is
// written unchanged to the joint's VelocityJointInterface every cycle; commands start at 0.
//   velocity_controllers/JointVelocityController       param joint,  std_msgs/Float64
//   velocity_controllers/JointGroupVelocityController  param joints, std_msgs/Float64MultiArray
// Topic: <robot ns>/<controller>/command. See forward_command_controller.hpp.
#include "servoloop/controllers/common/forward_command_controller.hpp"
#include "servoloop/controllers/common/forward_joint_group_command_controller.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"

namespace servoloop::controllers::velocity_controllers {

using JointVelocityController = ForwardCommandController<hardware_interface::VelocityJointInterface>;
using JointGroupVelocityController =
    ForwardJointGroupCommandController<hardware_interface::VelocityJointInterface>;

}  // namespace servoloop::controllers::velocity_controllers
