// The one instantiation of Controller<> for each of ros_control's joint and
// actuator interfaces (declared extern in controller.hpp).
#include "servoloop/controller_manager/controller.hpp"

namespace servoloop::controller_manager {

template class Controller<hardware_interface::JointStateInterface>;
template class Controller<hardware_interface::EffortJointInterface>;
template class Controller<hardware_interface::VelocityJointInterface>;
template class Controller<hardware_interface::PositionJointInterface>;
template class Controller<hardware_interface::EffortActuatorInterface>;
template class Controller<hardware_interface::VelocityActuatorInterface>;
template class Controller<hardware_interface::PositionActuatorInterface>;

}  // namespace servoloop::controller_manager
