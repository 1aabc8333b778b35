#include "parameter_bridge.hpp"

#include <cmath>
#include <iomanip>
#include <locale>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

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
  copy.copied = root;
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

namespace {

std::string quoted(const std::string& text) {
  YAML::Emitter out;
  out << YAML::DoubleQuoted << text;
  return out.c_str();
}

// The shortest text that reads back as the same double, always with a '.' or
// an exponent (100.0, not 100, which YAML would read as an integer).
std::string doubleText(double value) {
  if (std::isnan(value)) return ".nan";
  if (std::isinf(value)) return value > 0.0 ? ".inf" : "-.inf";
  std::string text;
  for (int digits = 15; digits <= 17; ++digits) {
    std::ostringstream out;
    out.imbue(std::locale::classic());
    out << std::setprecision(digits) << value;
    text = out.str();
    std::istringstream in(text);
    in.imbue(std::locale::classic());
    double back = 0.0;
    if (in >> back && back == value) break;
  }
  if (text.find_first_of(".eE") == std::string::npos) text += ".0";
  return text;
}

}  // namespace

// (XmlRpcValue's typed reads are not const; nothing here changes the value.)
std::string xmlRpcToYaml(XmlRpc::XmlRpcValue& value) {
  switch (value.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean:
      return static_cast<bool>(value) ? "true" : "false";
    case XmlRpc::XmlRpcValue::TypeInt:
      return std::to_string(static_cast<int>(value));
    case XmlRpc::XmlRpcValue::TypeDouble:
      return doubleText(static_cast<double>(value));
    case XmlRpc::XmlRpcValue::TypeString:
      return quoted(static_cast<std::string>(value));
    case XmlRpc::XmlRpcValue::TypeArray: {
      std::string text = "[";
      for (int i = 0; i < value.size(); ++i) text += (i > 0 ? ", " : "") + xmlRpcToYaml(value[i]);
      return text + "]";
    }
    case XmlRpc::XmlRpcValue::TypeStruct: {
      std::string text = "{";
      bool first = true;
      for (auto& [key, member] : value) {
        text += (first ? "" : ", ") + quoted(key) + ": " + xmlRpcToYaml(member);
        first = false;
      }
      return text + "}";
    }
    case XmlRpc::XmlRpcValue::TypeDateTime:
    case XmlRpc::XmlRpcValue::TypeBase64:
      return quoted(value.toXml());
    case XmlRpc::XmlRpcValue::TypeInvalid:
      break;
  }
  return "null";
}

namespace {

// The node at a slash-separated name under root; nullopt when missing.
std::optional<YAML::Node> childAt(const YAML::Node& root, const std::string& name) {
  YAML::Node node;
  node.reset(root);
  std::size_t start = 0;
  while (start < name.size()) {
    std::size_t end = name.find('/', start);
    if (end == std::string::npos) end = name.size();
    if (end > start) {
      if (!node.IsMap()) return std::nullopt;
      const YAML::Node& parent = node;
      const YAML::Node child = parent[name.substr(start, end - start)];
      if (!child.IsDefined()) return std::nullopt;
      node.reset(child);
    }
    start = end + 1;
  }
  return node;
}

void rosLeaves(const std::string& prefix, XmlRpc::XmlRpcValue& value,
               std::vector<std::pair<std::string, XmlRpc::XmlRpcValue*>>& out) {
  if (value.getType() == XmlRpc::XmlRpcValue::TypeStruct && value.size() > 0) {
    for (auto& [key, member] : value) rosLeaves(prefix + "/" + key, member, out);
    return;
  }
  out.emplace_back(prefix, &value);
}

}  // namespace

std::vector<ChangedParameter> changedParameters(const std::string& name, XmlRpc::XmlRpcValue& ros_value,
                                                const YAML::Node& copied,
                                                const std::map<std::string, std::string>& synced) {
  std::vector<std::pair<std::string, XmlRpc::XmlRpcValue*>> leaves;
  rosLeaves(name, ros_value, leaves);
  std::vector<ChangedParameter> changed;
  for (const auto& [leaf_name, leaf] : leaves) {
    // What the node was last given for this name: passed on at an earlier
    // load, else as the bridge copied it at start.
    std::optional<std::string> known;
    if (const auto it = synced.find(leaf_name); it != synced.end()) {
      known = it->second;
    } else if (const std::optional<YAML::Node> before = childAt(copied, leaf_name)) {
      known = yamlToXmlRpc(*before).toXml();
    }
    std::string xml_rpc = leaf->toXml();
    if (known && *known == xml_rpc) continue;
    changed.push_back({leaf_name, xmlRpcToYaml(*leaf), std::move(xml_rpc)});
  }
  return changed;
}

int passControllerParametersOn(NodeLink& link, const std::string& controller, const YAML::Node& copied,
                               std::map<std::string, std::string>& synced) {
  if (controller.empty() || controller.front() == '~') return 0;
  const std::string name = link.resolve(controller);
  // Only a name inside the robot's namespace (not the namespace itself, one
  // above it, or another robot's).
  const std::string root = link.resolve("");
  const std::string prefix = root == "/" ? root : root + "/";
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return 0;
  for (const nlohmann::json& loaded : link.call("control.list").at("controllers")) {
    if (loaded.value("name", "") == controller) return 0;
  }
  XmlRpc::XmlRpcValue value;
  try {
    if (!ros::param::get(name, value) || value.getType() != XmlRpc::XmlRpcValue::TypeStruct) return 0;
  } catch (const ros::InvalidNameException&) {
    return 0;  // not a name ROS has: the node's own parameters (and error) stand
  }
  const std::vector<ChangedParameter> changed = changedParameters(name, value, copied, synced);
  for (const ChangedParameter& parameter : changed) {
    link.call("param.set", {{"name", parameter.name}, {"value", parameter.yaml}});
    synced[parameter.name] = parameter.xml_rpc;
  }
  return static_cast<int>(changed.size());
}

}  // namespace servoloop::ros1
