#include "node_link.hpp"

#include <algorithm>
#include <mutex>
#include <utility>
#include <vector>

#include "servoloop/core/errors.hpp"
#include "servoloop/ipc/ipc_client.hpp"
#include "servoloop/ipc/ipc_socket_path.hpp"
#include "servoloop/params/parameter_store.hpp"

namespace servoloop::ros1 {

struct NodeLink::Impl {
  std::mutex mutex;
  ipc::IpcClient client;
};

NodeLink::NodeLink(std::string node_namespace)
    : node_namespace_(std::move(node_namespace)), impl_(std::make_unique<Impl>()) {
  impl_->client = ipc::IpcClient::connectToNode(node_namespace_);
}

NodeLink::~NodeLink() = default;

nlohmann::json NodeLink::call(std::string_view op, const nlohmann::json& args, double timeout_s) {
  std::lock_guard lock(impl_->mutex);
  return impl_->client.call(op, args, timeout_s);
}

std::string NodeLink::resolve(std::string_view relative) const { return params::resolveName(node_namespace_, relative); }

std::optional<nlohmann::json> NodeLink::readStream(double timeout_s) {
  std::lock_guard lock(impl_->mutex);
  return impl_->client.readStream(timeout_s > 0.0 ? timeout_s : 1e-6);
}

std::string pickNodeNamespace(const std::string& requested) {
  if (!requested.empty()) return requested;
  std::vector<std::string> running;
  for (const auto& entry : ipc::listNodes()) {
    if (entry.accepting && entry.node_name != "/") running.push_back(entry.node_name);
  }
  if (running.size() == 1) return running.front();
  if (running.empty()) {
    throw Error("no servoloop node is running; start one with `servoloop launch <launch file>`, then "
                "`servoloop ros1-bridge`");
  }
  std::string names;
  for (const auto& name : running) names += (names.empty() ? "" : ", ") + name;
  throw Error("several servoloop nodes are running (" + names + "); choose one with -N NAMESPACE");
}

std::string namespaceStem(const std::string& node_namespace) {
  std::string stem = ipc::socketStemFor(node_namespace);
  for (char& c : stem) {
    if (c == '.' || c == '-') c = '_';  // ROS names take letters, digits and '_'
  }
  return stem;
}

}  // namespace servoloop::ros1
