#include "node_connection.hpp"

#include <csignal>
#include <ctime>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>
#include <thread>

#include "servoloop/ipc/ipc_socket_path.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::cli {
namespace {


const char* const kStartHint = "start one with `servoloop launch <launch file>`";

std::vector<servoloop::ipc::IpcNodeEntry> acceptingNodes() {
  std::vector<servoloop::ipc::IpcNodeEntry> accepting;
  for (auto& entry : servoloop::ipc::listNodes()) {
    if (entry.accepting) accepting.push_back(std::move(entry));
  }
  return accepting;
}

std::string joinNames(const std::vector<servoloop::ipc::IpcNodeEntry>& nodes) {
  std::string names;
  for (const auto& node : nodes) {
    if (!names.empty()) names += ", ";
    names += node.node_name;
  }
  return names;
}

// The only robot node, or the world's socket when nothing else is served;
// nullopt when no node runs. Throws when several robot nodes run.
std::optional<servoloop::ipc::IpcNodeEntry> onlyNode(const std::vector<servoloop::ipc::IpcNodeEntry>& accepting) {
  std::vector<servoloop::ipc::IpcNodeEntry> robots;
  for (const auto& node : accepting) {
    if (node.node_name != "/") robots.push_back(node);
  }
  if (robots.size() == 1) return robots.front();
  if (robots.size() > 1) {
    throw Error("several servoloop nodes are running (" + joinNames(robots) +
                "); choose one with --namespace");
  }
  if (!accepting.empty()) return accepting.front();
  return std::nullopt;
}

servoloop::ipc::IpcClient connectTo(const servoloop::ipc::IpcNodeEntry& node) {
  servoloop::ipc::IpcClient client;
  client.connect(node.socket_path);
  return client;
}

bool isPrefixNamespace(const std::string& ns, const std::string& name) {
  if (ns == "/") return false;
  return name.size() > ns.size() && name.compare(0, ns.size(), ns) == 0 && name[ns.size()] == '/';
}

std::string formatSeconds(double seconds) {
  std::ostringstream text;
  text << seconds;
  return text.str();
}

volatile std::sig_atomic_t g_stop_signal = 0;

extern "C" void onStopSignal(int signal) { g_stop_signal = signal; }

}  // namespace

std::string normalizeNamespace(std::string_view ns) {
  if (ns.empty()) return "";
  std::string normalized(ns);
  while (normalized.size() > 1 && normalized.back() == '/') normalized.pop_back();
  if (normalized.front() != '/') normalized.insert(normalized.begin(), '/');
  return normalized;
}

std::string resolveName(std::string_view ns, std::string_view name) {
  if (!name.empty() && name.front() == '/') return std::string(name);
  std::string base = normalizeNamespace(ns);
  if (base.empty() || base == "/") return "/" + std::string(name);
  return base + "/" + std::string(name);
}

CLI::Option* addNamespaceOption(CLI::App& command, std::string& ns) {
  return command
      .add_option("-N,--namespace", ns,
                  "Robot namespace of the node, e.g. /one_DOF_robot (default: the only node "
                  "running)")
      ->type_name("NS");
}

std::string describeRunningNodes() {
  const auto accepting = acceptingNodes();
  if (accepting.empty()) {
    return "no servoloop node is running (run directory " + servoloop::ipc::ipcRunDirectory().string() + ")";
  }
  return "running nodes: " + joinNames(accepting);
}

servoloop::ipc::IpcClient connectToRobotNode(const std::string& ns_option, double wait_s, bool wait) {
  const std::string ns = normalizeNamespace(ns_option);
  if (!ns.empty()) {
    if (wait && !servoloop::ipc::waitForNode(ns, wait_s)) {
      throw Error("no servoloop node for namespace '" + ns + "' appeared within " +
                  formatSeconds(wait_s) + " s (" + describeRunningNodes() + "); " + kStartHint +
                  " or raise --timeout");
    }
    try {
      return servoloop::ipc::IpcClient::connectToNode(ns);
    } catch (const Error& error) {
      // With no node at all, say so plainly: files a node left behind (its
      // .lock, a socket nobody accepts on) are not worth the user's attention.
      if (std::string_view(error.what()).starts_with("no servoloop node") && acceptingNodes().empty()) {
        throw Error("no servoloop node is running (looked for namespace '" + ns + "' in run directory " +
                    servoloop::ipc::ipcRunDirectory().string() + "); " + kStartHint);
      }
      throw Error(std::string(error.what()) + " (" + describeRunningNodes() + ")");
    }
  }

  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(wait_s));
  while (true) {
    if (auto node = onlyNode(acceptingNodes())) return connectTo(*node);
    if (!wait || (wait_s > 0.0 && std::chrono::steady_clock::now() >= deadline)) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  std::string message = "no servoloop node is running (run directory " +
                        servoloop::ipc::ipcRunDirectory().string() + ")";
  if (wait) message += " after waiting " + formatSeconds(wait_s) + " s";
  throw Error(message + "; " + kStartHint);
}

servoloop::ipc::IpcClient connectForName(const std::string& name, const std::string& ns_option) {
  if (!normalizeNamespace(ns_option).empty()) return connectToRobotNode(ns_option);
  const auto accepting = acceptingNodes();
  const servoloop::ipc::IpcNodeEntry* best = nullptr;
  for (const auto& node : accepting) {
    if (isPrefixNamespace(node.node_name, name) &&
        (best == nullptr || node.node_name.size() > best->node_name.size())) {
      best = &node;
    }
  }
  if (best != nullptr) return connectTo(*best);
  if (auto node = onlyNode(accepting)) return connectTo(*node);
  throw Error("no servoloop node is running for '" + name + "' (run directory " +
              servoloop::ipc::ipcRunDirectory().string() + "); " + kStartHint);
}

servoloop::ipc::IpcClient connectToWorld() {
  const auto accepting = acceptingNodes();
  for (const auto& node : accepting) {
    if (node.node_name == "/") return connectTo(node);
  }
  if (accepting.size() == 1) return connectTo(accepting.front());
  if (accepting.empty()) {
    throw Error("no servoloop world is running (run directory " + servoloop::ipc::ipcRunDirectory().string() +
                "); " + kStartHint);
  }
  throw Error("several servoloop nodes are running (" + joinNames(accepting) +
              ") and none serves the world's socket (default.sock); stop the others or "
              "launch a world");
}

std::vector<std::string> runningNodeNames() {
  std::vector<std::string> names;
  bool any_robot = false;
  for (const auto& node : acceptingNodes()) {
    names.push_back(node.node_name);
    any_robot |= node.node_name != "/";
  }
  // Beside robot sockets, the world's socket shows nothing of its own (its
  // robots are reached through theirs).
  if (any_robot) std::erase(names, std::string("/"));
  return names;
}

servoloop::ipc::IpcClient connectToNodeNamed(const std::string& node_name) {
  for (const auto& node : acceptingNodes()) {
    if (node.node_name == node_name) return connectTo(node);
  }
  throw Error("the servoloop node '" + node_name + "' is no longer running (" + describeRunningNodes() + ")");
}

StreamMessage parseStreamMessage(const nlohmann::json& stream) {
  StreamMessage message;
  message.topic = stream.value("stream", "");
  message.type = stream.value("type", "");
  if (stream.contains("stamp") && stream["stamp"].is_number()) {
    message.stamp = stream["stamp"].get<double>();
  }
  if (stream.contains("msg")) {
    message.msg = stream["msg"];
  } else {
    message.msg = stream;
    for (const char* key : {"stream", "type"}) message.msg.erase(key);
  }
  if (!message.stamp && message.msg.is_object() && message.msg.contains("stamp") &&
      message.msg["stamp"].is_number()) {
    message.stamp = message.msg["stamp"].get<double>();
  }
  return message;
}

void installStopSignalHandlers() {
  struct sigaction action {};
  action.sa_handler = onStopSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // no SA_RESTART: blocking reads return EINTR and notice the flag
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool stopRequested() { return g_stop_signal != 0; }

int stopSignal() { return static_cast<int>(g_stop_signal); }

bool sleepUnlessStopped(double seconds) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(std::max(seconds, 0.0)));
  while (!stopRequested()) {
    const auto now = std::chrono::steady_clock::now();
    if (now >= deadline) return true;
    // Short slices: a signal may arrive just before the sleep starts.
    const auto slice = std::min<std::chrono::steady_clock::duration>(
        deadline - now, std::chrono::milliseconds(50));
    std::this_thread::sleep_for(slice);
  }
  return false;
}

std::string existingFileArgument(const std::string& path, std::string_view what) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (!fs::is_regular_file(path, error)) {
    throw Error(std::string(what) + " '" + path + "' does not exist or is not a file");
  }
  return fs::absolute(path).lexically_normal().string();
}

}  // namespace servoloop::cli
