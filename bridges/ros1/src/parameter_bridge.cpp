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

nlohmann::json xmlRpcToJson(XmlRpc::XmlRpcValue& value) {
  switch (value.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean:
      return static_cast<bool>(value);
    case XmlRpc::XmlRpcValue::TypeInt:
      return static_cast<int>(value);
    case XmlRpc::XmlRpcValue::TypeDouble:
      return static_cast<double>(value);
    case XmlRpc::XmlRpcValue::TypeString:
      return static_cast<std::string>(value);
    case XmlRpc::XmlRpcValue::TypeArray: {
      nlohmann::json out = nlohmann::json::array();
      for (int i = 0; i < value.size(); ++i) out.push_back(xmlRpcToJson(value[i]));
      return out;
    }
    case XmlRpc::XmlRpcValue::TypeStruct: {
      nlohmann::json out = nlohmann::json::object();
      for (auto& [key, member] : value) out[key] = xmlRpcToJson(member);
      return out;
    }
    case XmlRpc::XmlRpcValue::TypeDateTime:
    case XmlRpc::XmlRpcValue::TypeBase64:
      return value.toXml();
    case XmlRpc::XmlRpcValue::TypeInvalid:
      break;
  }
  return nullptr;
}

bool passControllerParametersOn(NodeLink& link, const std::string& controller) {
  const std::string name = link.resolve(controller);
  XmlRpc::XmlRpcValue value;
  try {
    if (!ros::param::get(name, value) || value.getType() != XmlRpc::XmlRpcValue::TypeStruct) return false;
  } catch (const ros::InvalidNameException&) {
    return false;  // not a name ROS has: the node's own parameters (and error) stand
  }
  link.call("param.set", {{"name", name}, {"value", xmlRpcToJson(value)}});
  return true;
}

}  // namespace servoloop::ros1
