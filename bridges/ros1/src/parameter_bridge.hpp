#pragma once
// What ROS nodes read from the parameter server, taken from the node once when
// the bridge starts: the node's parameters (controller configuration and the
// rest of the store, under their own names), the robot's expanded URDF as
// <ns>/robot_description (and /robot_description when the node runs one robot
// and nothing is there yet), and /use_sim_time (true: the bridge publishes /clock).
#include <map>
#include <string>
#include <vector>

#include <xmlrpcpp/XmlRpcValue.h>
#include <yaml-cpp/yaml.h>

#include "node_link.hpp"

namespace servoloop::ros1 {

struct ParameterCopy {
  int parameters = 0;  // parameters (leaves) set
  bool robot_description = false;
  YAML::Node copied;   // the node's parameters as the bridge set them in ROS (from the root)
};

ParameterCopy copyParametersToRos(NodeLink& link, bool use_sim_time);

// Before load_controller: ros_control's controller manager reads a
// controller's configuration from the ROS parameter server when it loads it.
// Of what ROS holds under <ns>/<controller>, the values that differ from what
// the node was last given (passed on at an earlier load, recorded in
// `synced`; else as the bridge copied them at start, `copied`) are passed to
// the node, each as YAML text so its type survives; the node's other values
// (a `servoloop param set` since, say) stay as they are. Returns how many were
// passed on: none for a private (~) name, a name outside the robot's
// namespace or the namespace itself, or a controller the node has loaded
// already (its load fails, as in ros_control).
int passControllerParametersOn(NodeLink& link, const std::string& controller, const YAML::Node& copied,
                               std::map<std::string, std::string>& synced);

// A leaf to pass on: its name, its value as YAML text (for the node) and as
// XML-RPC text (what `synced` records once it was passed on).
struct ChangedParameter {
  std::string name;
  std::string yaml;
  std::string xml_rpc;
};

// The leaves under `name` in `ros_value` (a dictionary as ROS holds it) that
// are new or differ from what the node was last given. `synced`: XML-RPC text
// of values passed on before, by name.
std::vector<ChangedParameter> changedParameters(const std::string& name, XmlRpc::XmlRpcValue& ros_value,
                                                const YAML::Node& copied,
                                                const std::map<std::string, std::string>& synced);

// YAML (as the node's param.dump writes it) to an XML-RPC value as rosparam
// types it: integers, doubles, booleans, strings, lists, dictionaries.
XmlRpc::XmlRpcValue yamlToXmlRpc(const YAML::Node& node);

// An XML-RPC value as YAML text (flow style) that loads back with its type:
// strings quoted, doubles always with a '.' or an exponent and as many
// digits as it takes to read back the same value (.inf, .nan included).
std::string xmlRpcToYaml(XmlRpc::XmlRpcValue& value);

}  // namespace servoloop::ros1
