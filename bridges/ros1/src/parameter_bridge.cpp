#include "parameter_bridge.hpp"

#include <ros/ros.h>

namespace servoloop::ros1 {

XmlRpc::XmlRpcValue yamlToXmlRpc(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Map: {
      XmlRpc::XmlRpcValue out;
      out.begin();  // makes it a struct even when empty
      for (const auto& entry : node) out[entry.first.as<std::string>()] = yamlToXmlRpc(entry.second);
      return out;
    }
    case YAML::NodeType::Sequence: {
      XmlRpc::XmlRpcValue out;
      out.setSize(static_cast<int>(node.size()));
      for (std::size_t i = 0; i < node.size(); ++i) out[static_cast<int>(i)] = yamlToXmlRpc(node[i]);
      return out;
    }
    case YAML::NodeType::Scalar: {
      // Quoted scalars stay strings; plain ones are typed as YAML types them.
      if (node.Tag() != "!") {
        int integer = 0;
        double number = 0.0;
        bool boolean = false;
        if (YAML::convert<int>::decode(node, integer)) return XmlRpc::XmlRpcValue(integer);
        if (YAML::convert<double>::decode(node, number)) return XmlRpc::XmlRpcValue(number);
        if (YAML::convert<bool>::decode(node, boolean)) return XmlRpc::XmlRpcValue(boolean);
      }
      return XmlRpc::XmlRpcValue(node.Scalar());
    }
    case YAML::NodeType::Null:
    case YAML::NodeType::Undefined:
      break;
  }
  return XmlRpc::XmlRpcValue(std::string());
}

namespace {

void setLeaves(const std::string& prefix, const YAML::Node& node, ParameterCopy& copy) {
  if (node.IsMap() && node.size() > 0) {
    for (const auto& entry : node) setLeaves(prefix + "/" + entry.first.as<std::string>(), entry.second, copy);
    return;
  }
  if (prefix.empty()) return;
  try {
    ros::param::set(prefix, yamlToXmlRpc(node));
    ++copy.parameters;
  } catch (const ros::InvalidNameException& e) {
    ROS_WARN("servoloop bridge: parameter %s stays in servoloop: ROS does not accept its name (%s)", prefix.c_str(),
             e.what());
  }
}

}  // namespace

ParameterCopy copyParametersToRos(NodeLink& link, bool use_sim_time) {
  ParameterCopy copy;
  const std::string yaml = link.call("param.dump", {{"namespace", "/"}}).value("yaml", "");
  const YAML::Node root = YAML::Load(yaml);
  // Leaf by leaf: setting a whole tree would replace what ROS nodes keep
  // beside servoloop's parameters under the same namespace.
  setLeaves("", root, copy);

  const std::string description = link.call("robot.description").value("urdf", "");
  if (!description.empty()) {
    ros::param::set(link.resolve("robot_description"), description);
    const auto robots = link.call("ping").value("robots", std::vector<std::string>{});
    if (robots.size() == 1 && !ros::param::has("/robot_description")) ros::param::set("/robot_description", description);
    copy.robot_description = true;
  }
  ros::param::set("/use_sim_time", use_sim_time);
  return copy;
}

}  // namespace servoloop::ros1
