#pragma once
// position_controllers' forward-command types: the commanded joint position (rad or m) is
// written unchanged to the joint's PositionJointInterface every cycle; commands start at the
// joints' current positions, so the joints hold where they are.
//   position_controllers/JointPositionController       param joint,  std_msgs/Float64
//   position_controllers/JointGroupPositionController  param joints, std_msgs/Float64MultiArray
// Topic: <robot ns>/<controller>/command. See forward_command_controller.hpp.
#include "servoloop/controllers/common/forward_command_controller.hpp"
#include "servoloop/controllers/common/forward_joint_group_command_controller.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"

namespace servoloop::controllers::position_controllers {

using JointPositionController = ForwardCommandController<hardware_interface::PositionJointInterface>;
using JointGroupPositionController =
    ForwardJointGroupCommandController<hardware_interface::PositionJointInterface>;

}  // namespace servoloop::controllers::position_controllers
