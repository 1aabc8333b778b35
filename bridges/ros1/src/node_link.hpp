#pragma once
// The bridge's connection to a running servoloop node over its IPC socket.
// Requests (topic.pub, control.*, param.*) may come from any thread, one at a
// time; stream messages (topic subscriptions) are read with readStream. The
// bridge opens two links: one for requests, one for streams, so a slow request
// never holds up the messages flowing to ROS.
//
// This header is C++17 (the ROS side of the bridge is built as C++17, which
// roscpp 1.15 needs); the link itself is built with the project's C++20.
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace servoloop::ros1 {

class NodeLink {
 public:
  // Connects to the node serving `node_namespace`; throws std::runtime_error
  // naming the namespace and how to start a node when none runs.
  explicit NodeLink(std::string node_namespace);
  ~NodeLink();
  NodeLink(const NodeLink&) = delete;
  NodeLink& operator=(const NodeLink&) = delete;

  // The node's reply fields; throws std::runtime_error with the node's error
  // text, or when the node does not answer within timeout_s.
  nlohmann::json call(std::string_view op, const nlohmann::json& args = nlohmann::json::object(),
                      double timeout_s = 10.0);

  // The next stream message, or nullopt after timeout_s (> 0). Throws
  // std::runtime_error when the node closes the connection (it ended).
  std::optional<nlohmann::json> readStream(double timeout_s);

  const std::string& nodeNamespace() const { return node_namespace_; }
  // A name under the node's namespace, resolved as ROS resolves it
  // ("joint_states" → "/one_DOF_robot/joint_states"; under "/": "/joint_states").
  std::string resolve(std::string_view relative) const;

 private:
  struct Impl;
  std::string node_namespace_;
  std::unique_ptr<Impl> impl_;
};

// The namespace to bridge: `requested` when given, else the only running
// node's; throws std::runtime_error when none or several run.
std::string pickNodeNamespace(const std::string& requested);

// A ROS name fragment for the namespace ("/arm/left" → "arm_left").
std::string namespaceStem(const std::string& node_namespace);

}  // namespace servoloop::ros1
