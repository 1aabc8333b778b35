#pragma once
// What ROS nodes read from the parameter server, taken from the node once when
// the bridge starts: the node's parameters (controller configuration and the
// rest of the store, under their own names), the robot's expanded URDF as
// <ns>/robot_description (and /robot_description when the node runs one robot
// and nothing is there yet), and /use_sim_time (true: the bridge publishes /clock).
#include <string>

#include <xmlrpcpp/XmlRpcValue.h>
#include <yaml-cpp/yaml.h>

#include "node_link.hpp"

namespace servoloop::ros1 {

struct ParameterCopy {
  int parameters = 0;  // parameters (leaves) set
  bool robot_description = false;
};

ParameterCopy copyParametersToRos(NodeLink& link, bool use_sim_time);

// Before load_controller: ros_control's controller manager reads a controller's
// configuration from the ROS parameter server when it loads it, so what ROS
// holds under <ns>/<controller> now (after a `rosparam load` or `rosparam set`
// since the bridge started) replaces the node's copy. Returns false, leaving
// the node's parameters as they are, when ROS holds no dictionary there.
bool passControllerParametersOn(NodeLink& link, const std::string& controller);

// An XML-RPC value (as rosparam stores it) to JSON: booleans, integers,
// doubles, strings, lists, dictionaries; dates and binary data as strings.
nlohmann::json xmlRpcToJson(XmlRpc::XmlRpcValue& value);

// YAML (as the node's param.dump writes it) to an XML-RPC value as rosparam
// types it: integers, doubles, booleans, strings, lists, dictionaries.
XmlRpc::XmlRpcValue yamlToXmlRpc(const YAML::Node& node);

}  // namespace servoloop::ros1
