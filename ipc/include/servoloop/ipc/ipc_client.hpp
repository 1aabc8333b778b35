#pragma once
// The command line's side of the node IPC: connect to a running node, send
// requests, read replies and pushed stream messages. Protocol: ipc_protocol.hpp.
//
//   IpcClient client = IpcClient::connectToNode("/one_DOF_robot");
//   nlohmann::json reply = client.call("list_controllers");   // throws on "ok": false
//
// One IpcClient is used by one thread at a time. Timeouts are in seconds; a
// timeout of 0 (or less) waits forever. Nothing here runs on the real-time thread.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "servoloop/ipc/ipc_unix_socket.hpp"

namespace servoloop::ipc {

class IpcClient {
 public:
  IpcClient() = default;
  ~IpcClient() = default;
  IpcClient(IpcClient&&) noexcept = default;
  IpcClient& operator=(IpcClient&&) noexcept = default;
  IpcClient(const IpcClient&) = delete;
  IpcClient& operator=(const IpcClient&) = delete;

  // Connects to the node serving `node_name` (socketPathFor(node_name)).
  static IpcClient connectToNode(std::string_view node_name, double timeout_s = 2.0);

  // Connects to the node socket at `socket_path`, retrying while the node's
  // accept queue is full for up to `timeout_s`. Throws servoloop::Error:
  //   "no servoloop node is running for namespace '/one_DOF_robot' (looked for
  //    <path>); start one with `servoloop launch <launch file>`"
  // when nothing listens there, and a clear message for permission problems,
  // an unsafe run directory, or a timeout.
  void connect(const std::filesystem::path& socket_path, double timeout_s = 2.0);

  bool isConnected() const { return fd_.valid(); }
  void close();
  const std::filesystem::path& socketPath() const { return socket_path_; }
  // The namespace of the connected node, e.g. "/one_DOF_robot".
  const std::string& nodeName() const { return node_name_; }

  // Sends `request` (an object with a string "op"; its "id" is overwritten
  // with a fresh one) and returns the reply with that id, whatever its "ok".
  // Stream messages that arrive meanwhile are kept for readStream(). Throws
  // servoloop::Error if not connected, on timeout, or when the node closes the
  // connection; a timed-out request's late reply is discarded when it comes.
  nlohmann::json request(nlohmann::json request, double timeout_s = 5.0);

  // request() for {"op": op, ...args}; returns the reply if "ok" is true and
  // throws servoloop::Error carrying the node's "error" text otherwise.
  nlohmann::json call(std::string_view op, const nlohmann::json& args = nlohmann::json::object(),
                      double timeout_s = 5.0);

  // Next pushed stream message ({"stream": ...}), or nullopt if none arrives
  // within `timeout_s`. Throws servoloop::Error when the node closes the
  // connection.
  std::optional<nlohmann::json> readStream(double timeout_s);

 private:
  using Deadline = std::chrono::steady_clock::time_point;  // max(): never

  static Deadline deadlineAfter(double timeout_s);
  // Next complete line from the node, parsed; nullopt once `deadline` passes.
  std::optional<nlohmann::json> readMessage(Deadline deadline, std::string_view waiting_for);
  void sendAll(const std::string& line, Deadline deadline, std::string_view op);
  [[noreturn]] void failDisconnected(std::string_view waiting_for);

  IpcFd fd_;
  std::filesystem::path socket_path_;
  std::string node_name_;
  std::string input_;              // received bytes not yet parsed
  std::size_t input_scanned_ = 0;  // prefix of input_ known to hold no '\n'
  std::string last_node_error_;    // an error the node sent outside any reply, for messages
  std::deque<nlohmann::json> streams_;
  std::int64_t next_id_ = 1;
};

// Waits until a node serving `node_name` accepts connections. Polls every 50 ms
// for up to `timeout_s` (0 = forever); true once one accepts, false on timeout.
// Throws servoloop::Error if the run directory is not private.
bool waitForNode(std::string_view node_name, double timeout_s);

// Same, for a socket path.
bool waitForSocket(const std::filesystem::path& socket_path, double timeout_s);

}  // namespace servoloop::ipc
