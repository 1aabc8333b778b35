#pragma once
// Finding the running servoloop node a command should talk to, and the pieces
// every client command shares (the --namespace option, SIGINT/SIGTERM flags).
//
// A node serves one socket per robot namespace, plus the world's socket
// (`default.sock`, node name "/"). A command picks:
//   - the node named by --namespace, if given;
//   - for a topic or parameter name, the node whose namespace prefixes it;
//   - otherwise the only robot node running (or the world's socket if that is
//     all there is).
// Every failure names what was looked for and lists the nodes that are running.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "servoloop/ipc/ipc_client.hpp"

namespace servoloop::cli {

// "/one_DOF_robot" for "one_DOF_robot", "/one_DOF_robot/" or "/one_DOF_robot";
// "" stays "" (no namespace chosen), "/" stays "/".
std::string normalizeNamespace(std::string_view ns);

// A topic or parameter name made absolute: an absolute name is kept; a
// relative one is put under `ns` (or "/" when ns is empty).
std::string resolveName(std::string_view ns, std::string_view name);

// Adds `--namespace NS` (also `-N`) selecting the node by robot namespace.
CLI::Option* addNamespaceOption(CLI::App& command, std::string& ns);

// "running nodes: /a, /b" or "no servoloop node is running (run directory <dir>)".
std::string describeRunningNodes();

// Connects to the node for `ns` (normalized), or when `ns` is empty to the only
// robot node running. Waits up to `wait_s` seconds for such a node to accept
// (0 with wait == true: forever; wait == false: a single look). Throws
// servoloop::Error naming the namespace, the running nodes and the fix.
servoloop::ipc::IpcClient connectToRobotNode(const std::string& ns, double wait_s = 0.0,
                                                 bool wait = false);

// Connects to the node serving `name` (a topic or parameter, absolute): the
// --namespace node if `ns` is set, else the longest running namespace that
// prefixes `name`, else the only robot node (or the world's socket).
servoloop::ipc::IpcClient connectForName(const std::string& name, const std::string& ns);

// Connects to the world: default.sock if it is served, else the only node.
servoloop::ipc::IpcClient connectToWorld();

// The name of every node accepting connections now, sorted (e.g. "/arm/left",
// "/one_DOF_robot"; "/" for a world's socket, only when no robot's is there).
std::vector<std::string> runningNodeNames();

// Connects to the running node of that exact name (as runningNodeNames gives it).
servoloop::ipc::IpcClient connectToNodeNamed(const std::string& node_name);

// One message a node pushed on a `topic.subscribe` stream. The node sends
// {"stream": TOPIC, "type": T, "stamp": S, "msg": {...}}; fields given inline
// (no "msg") are accepted too, and a missing "stamp" is taken from the message.
struct StreamMessage {
  std::string topic;
  std::string type;
  std::optional<double> stamp;  // simulated seconds
  nlohmann::json msg;
};
StreamMessage parseStreamMessage(const nlohmann::json& stream);

// Installs handlers so SIGINT and SIGTERM set a flag instead of killing the
// process; stopRequested() reads it. Idempotent.
void installStopSignalHandlers();
bool stopRequested();
// The signal that set the flag (SIGINT/SIGTERM), 0 if none.
int stopSignal();

// Sleeps up to `seconds`, returning early (false) when a stop was requested.
bool sleepUnlessStopped(double seconds);

// Absolute path of an existing regular file given on the command line; throws
// servoloop::Error "<what> '<path>' does not exist" otherwise.
std::string existingFileArgument(const std::string& path, std::string_view what);

}  // namespace servoloop::cli
