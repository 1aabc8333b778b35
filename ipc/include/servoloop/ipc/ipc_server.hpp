#pragma once
// The node's IPC server: answers the command line's requests on a Unix socket.
//
// Protocol (newline-delimited JSON; details in ipc_protocol.hpp and
// docs/ipc_protocol.md):
//   request  {"id": 7, "op": "list_controllers", ...}
//   reply    {"id": 7, "ok": true, ...}  or  {"id": 7, "ok": false, "error": "..."}
//   stream   {"stream": "<name>", ...}   pushed to subscribed connections
//
// One service thread serves every connection with poll(); there is no thread
// per client, and the real-time loop never touches any of this. Sockets are
// non-blocking and each connection's output queue is bounded, so a client that
// stops reading is dropped instead of stalling the node.
//
// Usage:
//   IpcServer server(socketPathFor("/one_DOF_robot"),
//                    [&](const nlohmann::json& request, IpcConnection& connection) {
//                      if (request["op"] == "ping") return nlohmann::json{{"pong", true}};
//                      throw servoloop::Error("unknown op '" + request["op"].get<std::string>() + "'");
//                    });
//   server.start();
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string_view>
#include <thread>
#include <vector>

#include <sys/types.h>

#include <nlohmann/json.hpp>

#include "servoloop/ipc/ipc_connection.hpp"
#include "servoloop/ipc/ipc_unix_socket.hpp"

namespace servoloop::ipc {

// Counters for tests and diagnostics; each only grows while the server runs.
struct IpcServerStats {
  std::uint64_t connections_accepted = 0;
  std::uint64_t requests_handled = 0;       // lines that reached the handler
  std::uint64_t requests_rejected = 0;      // lines answered with a protocol error
  std::uint64_t clients_dropped_slow = 0;   // output queue overflowed
  std::uint64_t clients_dropped_oversized = 0;
};

class IpcServer {
 public:
  // Runs on the service thread, one request at a time; it should return
  // promptly since every client waits meanwhile. `request` is an object with a
  // string "op" (already checked). Its return value becomes the reply:
  //   - null or an object without "ok": {"id", "ok": true} plus its fields;
  //   - an object with "ok": sent as it is, with "id" set ("ok": false should
  //     carry "error"; a generic one is added if it does not);
  //   - any other value v: {"id", "ok": true, "result": v};
  //   - IpcServer::deferredReply(): nothing now; the handler (or a thread it
  //     hands the work to) later sends makeIpcOkReply/makeIpcErrorReply with
  //     the request's id through connection.sendDeferredReply().
  // An exception becomes {"id", "ok": false, "error": what()} and the server
  // carries on.
  using Handler =
      std::function<nlohmann::json(const nlohmann::json& request, IpcConnection& connection)>;

  // The marker a handler returns when it will reply later itself.
  static nlohmann::json deferredReply() {
    return nlohmann::json(nlohmann::json::value_t::discarded);
  }

  // Most simultaneous connections; more are told so and closed.
  static constexpr std::size_t kMaxConnections = 256;

  IpcServer(std::filesystem::path socket_path, Handler handler);
  ~IpcServer();
  IpcServer(const IpcServer&) = delete;
  IpcServer& operator=(const IpcServer&) = delete;

  // Creates the socket directory (private, see ensurePrivateDirectory), takes
  // the node's lock file "<stem>.lock" next to the socket, replaces a stale
  // socket file nobody listens on, and starts the service thread. Throws
  // servoloop::Error if another node holds that socket, the directory is not
  // private, or the socket cannot be made. Does nothing if already running.
  void start();

  // Closes every connection (running their onClose callbacks), removes the
  // socket file and joins the service thread. Safe to call twice; the
  // destructor calls it. Throws servoloop::Error if called from the service
  // thread itself (a handler or close callback), which would wait forever.
  void stop();

  bool isRunning() const { return running_.load(); }
  const std::filesystem::path& socketPath() const { return socket_path_; }
  std::size_t connectionCount() const { return connection_count_.load(); }
  IpcServerStats stats() const;

 private:
  void serviceLoop();
  void acceptConnections();
  void readFrom(IpcConnection& connection);
  void handleInput(IpcConnection& connection);
  void handleLine(IpcConnection& connection, std::string_view line);
  nlohmann::json replyFor(const nlohmann::json& request, IpcConnection& connection);
  void rejectOversized(IpcConnection& connection);
  // Closes connections that failed, finished, or outstayed their grace period;
  // returns the next grace deadline, if any, for poll()'s timeout.
  std::chrono::steady_clock::time_point reapConnections();
  void closeConnection(IpcConnection& connection);
  void releaseSocket();

  const std::filesystem::path socket_path_;
  const std::filesystem::path lock_path_;
  Handler handler_;

  std::mutex lifecycle_mutex_;  // serialises start() and stop()
  std::atomic<bool> running_{false};
  std::atomic<bool> stop_requested_{false};
  IpcFd listen_fd_;
  IpcFd wake_fd_;   // eventfd: stop() and other threads' send() wake poll()
  IpcFd lock_fd_;   // flock held for the server's life: one node per socket
  ino_t socket_inode_ = 0;
  std::thread service_thread_;

  // Service thread only (and stop() after joining it).
  std::vector<std::shared_ptr<IpcConnection>> connections_;
  std::uint64_t next_connection_id_ = 1;
  std::chrono::steady_clock::time_point accept_paused_until_{};

  std::atomic<std::size_t> connection_count_{0};
  std::atomic<std::uint64_t> connections_accepted_{0};
  std::atomic<std::uint64_t> requests_handled_{0};
  std::atomic<std::uint64_t> requests_rejected_{0};
  std::atomic<std::uint64_t> clients_dropped_slow_{0};
  std::atomic<std::uint64_t> clients_dropped_oversized_{0};
};

}  // namespace servoloop::ipc
