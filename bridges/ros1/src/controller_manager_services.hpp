#pragma once
// ros_control's controller_manager services under <ns>/controller_manager/,
// answered by the node's control.* operations with ros_control's request and
// response semantics: a request the node refuses is answered ok=false (the
// call itself succeeds) and the node's reason is logged.
#include <string>
#include <vector>

#include <ros/node_handle.h>
#include <ros/service_server.h>

#include "node_link.hpp"

namespace servoloop::ros1 {

class ControllerManagerServices {
 public:
  ControllerManagerServices(ros::NodeHandle& nh, NodeLink& link);

 private:
  std::vector<ros::ServiceServer> servers_;
};

// ros_control's name for a servoloop controller state.
const char* rosControlState(const std::string& servoloop_state);
// ros_control's name for a hardware interface, its C++ type
// ("EffortJointInterface" → "hardware_interface::EffortJointInterface").
std::string rosControlInterfaceName(const std::string& servoloop_interface);

}  // namespace servoloop::ros1
