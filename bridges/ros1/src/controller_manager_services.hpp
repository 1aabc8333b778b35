#pragma once
// ros_control's controller_manager services under <ns>/controller_manager/,
// answered by the node's control.* operations with ros_control's request and
// response semantics: a request the node refuses is answered ok=false (the
// call itself succeeds) and the node's reason is logged.
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include <ros/node_handle.h>
#include <ros/service_server.h>
#include <yaml-cpp/yaml.h>

#include "node_link.hpp"

namespace servoloop::ros1 {

class ControllerManagerServices {
 public:
  // copied_parameters: what the bridge copied to the parameter server at
  // start (ParameterCopy::copied), against which load_controller finds the
  // configuration changed in ROS since.
  ControllerManagerServices(ros::NodeHandle& nh, NodeLink& link, YAML::Node copied_parameters);

 private:
  std::vector<ros::ServiceServer> servers_;
  YAML::Node copied_parameters_;
  std::map<std::string, std::string> synced_parameters_;  // passed on by earlier loads
  std::mutex load_mutex_;  // one load_controller at a time (as ros_control serves them); guards the two above
};

// ros_control's name for a servoloop controller state.
const char* rosControlState(const std::string& servoloop_state);
// ros_control's name for a hardware interface, its C++ type
// ("EffortJointInterface" → "hardware_interface::EffortJointInterface").
std::string rosControlInterfaceName(const std::string& servoloop_interface);

}  // namespace servoloop::ros1
