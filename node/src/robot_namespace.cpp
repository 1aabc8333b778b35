#include "servoloop/node/robot_namespace.hpp"

#include <cstring>

#include <fmt/format.h>
#include <tinyxml2.h>

#include "servoloop/ipc/ipc_socket_path.hpp"
#include "servoloop/params/parameter_store.hpp"
#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/xml_error_text.hpp"

namespace servoloop::node {
namespace {

constexpr const char* kRosControlPlugin = "libgazebo_ros_control.so";

std::string trimmed(const char* text) {
  std::string value = text == nullptr ? "" : text;
  const auto first = value.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  const auto last = value.find_last_not_of(" \t\r\n");
  return value.substr(first, last - first + 1);
}

}  // namespace

std::string urdfRobotNamespace(const std::string& urdf_xml, const std::string& source_name) {
  tinyxml2::XMLDocument document;
  if (document.Parse(urdf_xml.c_str(), urdf_xml.size()) != tinyxml2::XML_SUCCESS) {
    throw ConfigError(source_name + ": not valid XML (line " + std::to_string(document.ErrorLineNum()) +
                      "): " + xmlErrorWords(document.ErrorName(), document.ErrorStr() ? document.ErrorStr() : "") +
                      "; check the robot description");
  }
  const tinyxml2::XMLElement* robot = document.FirstChildElement("robot");
  if (robot == nullptr) return "";
  for (const auto* gazebo = robot->FirstChildElement("gazebo"); gazebo != nullptr;
       gazebo = gazebo->NextSiblingElement("gazebo")) {
    for (const auto* plugin = gazebo->FirstChildElement("plugin"); plugin != nullptr;
         plugin = plugin->NextSiblingElement("plugin")) {
      const char* filename = plugin->Attribute("filename");
      if (filename == nullptr || std::strcmp(filename, kRosControlPlugin) != 0) continue;
      const auto* ns = plugin->FirstChildElement("robotNamespace");
      if (ns == nullptr) continue;
      const std::string value = trimmed(ns->GetText());
      if (!value.empty()) return value;
    }
  }
  return "";
}

std::string resolveRobotNamespace(const std::string& urdf_xml, const std::string& source_name,
                                  const std::string& launch_namespace, const std::string& robot_name) {
  std::string chosen = urdfRobotNamespace(urdf_xml, source_name);
  std::string origin = "<robotNamespace> of its gazebo_ros_control plugin";
  if (chosen.empty()) {
    chosen = launch_namespace;
    origin = "the launch file's namespace";
  }
  if (chosen.empty()) {
    chosen = "/" + robot_name;
    origin = "its model name '" + robot_name + "'";
  }
  std::string resolved;
  try {
    resolved = params::resolveName("/", chosen);
    // It prefixes every topic of the robot: it follows the topic name rules.
    if (resolved != "/") realtime::TopicBus::normalizeTopicName(resolved);
  } catch (const Error& e) {
    throw ConfigError(source_name + ": robot namespace '" + chosen + "' (from " + origin + "): " + e.what() +
                      "; give the robot a namespace that is a ROS name (launch file: namespace: /my_robot; "
                      "spawn-model: -N /my_robot)");
  }
  return resolved;
}

std::string spawnNamespaceProblem(const std::string& ns) {
  if (ns == "/" || ns == "/default") {
    return "is reserved: '/' and '/default' name the node's own socket (default.sock); give the robot a namespace "
           "of its own, e.g. -N /my_robot";
  }
  if (ns.size() > kMaxSpawnNamespaceLength) {
    return "is " + std::to_string(ns.size()) + " characters long; a robot namespace may have at most " +
           std::to_string(kMaxSpawnNamespaceLength) + " (it names the robot's socket); give a shorter one";
  }
  const std::string socket = ipc::socketPathFor(ns).string();
  if (socket.size() > 107) {
    return "gives the socket path '" + socket + "' of " + std::to_string(socket.size()) +
           " characters, more than a Unix socket takes (107); give a shorter namespace or set SERVOLOOP_RUN_DIR to "
           "a shorter folder";
  }
  return "";
}

std::string ignoredLaunchNamespace(const std::string& urdf_xml, const std::string& source_name,
                                   const std::string& launch_namespace) {
  const std::string from_urdf = urdfRobotNamespace(urdf_xml, source_name);
  if (from_urdf.empty() || launch_namespace.empty()) return {};
  std::string asked = launch_namespace;
  std::string resolved = from_urdf;
  try {
    asked = params::resolveName("/", launch_namespace);
    resolved = params::resolveName("/", from_urdf);
  } catch (const Error&) {
    return {};  // resolveRobotNamespace reports a name that is not a ROS name
  }
  // "/" is what a ROS launch file without <group ns> gives: nothing was asked.
  if (asked == "/" || asked == resolved) return {};
  return fmt::format("{}: the robot's namespace is '{}' from the <robotNamespace> of its gazebo_ros_control plugin "
                     "(it wins, as in Gazebo); the launch file's namespace '{}' is not used, and the robot's topics "
                     "and parameters live under '{}'; remove one of the two, or make them the same",
                     source_name, resolved, launch_namespace, resolved);
}

}  // namespace servoloop::node
