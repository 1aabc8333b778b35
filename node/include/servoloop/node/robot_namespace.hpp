#pragma once
// Which namespace a robot's controllers, parameters, topics and IPC socket
// live under. Non-real-time.
#include <cstddef>
#include <string>

namespace servoloop::node {

// The robotNamespace a URDF gives its gazebo_ros_control plugin
// (<gazebo><plugin filename="libgazebo_ros_control.so"><robotNamespace>), as
// the seed's URDF does; "" when there is none. Throws servoloop::ConfigError
// naming source_name when the text is not XML.
std::string urdfRobotNamespace(const std::string& urdf_xml, const std::string& source_name);

// The rule of the command line's contract (CLI.md, "Robot namespace"): the
// URDF's robotNamespace wins, else launch_namespace, else "/<robot_name>".
// The result is normalised ("/one_DOF_robot"); robot_name is the model name
// given at spawn time, or the URDF's <robot name> when none was given.
std::string resolveRobotNamespace(const std::string& urdf_xml, const std::string& source_name,
                                  const std::string& launch_namespace, const std::string& robot_name);

// The warning to give when the URDF's robotNamespace overrides a different
// namespace the launch file asked for (its commands would otherwise go
// nowhere without a word); "" when nothing was overridden. A launch
// namespace of "/" (a ROS launch file without <group ns>) asks for nothing.
std::string ignoredLaunchNamespace(const std::string& urdf_xml, const std::string& source_name,
                                   const std::string& launch_namespace);

// The longest robot namespace a spawn into a running node takes: it names
// the robot's socket (<run dir>/<stem>.sock, a Unix socket path of at most
// 107 bytes) and prefixes every one of its topics and parameters.
inline constexpr std::size_t kMaxSpawnNamespaceLength = 64;

// Why a robot spawned into a running node cannot have the resolved namespace
// ns ("/a/b"), or "" when it can: "/" and "/default" are reserved (they name
// the node's own socket, default.sock), longer than kMaxSpawnNamespaceLength,
// or a socket path that does not fit. The text follows "robot namespace '<ns>' ".
std::string spawnNamespaceProblem(const std::string& ns);

}  // namespace servoloop::node
