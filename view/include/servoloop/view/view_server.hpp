#pragma once
// The browser view of a running world (docs/view.md): a page with every
// robot and object in 3D, moving with the simulation, served with three.js
// from Debian's libjs-three over HTTP and a WebSocket.
//
//   ViewServer view(options, [] { return connectionToTheNode(); });
//   view.start();            // throws ConfigError for a port in use
//   ... view.url() ...
//   view.stop();
//
// The view asks the node what it shows over the node's IPC operations
// (view.scene, view.frame, control.list, ...): inside the launching process
// (`servoloop launch --view`) and from another one (`servoloop view`) alike,
// so it never touches the world's thread. The node takes the snapshots the
// frames come from between two segments of cycles (node/world_snapshot.hpp).
//
// Threads: the server's (HTTP and WebSocket), one that sends frames to the
// pages (up to `frame_rate_hz`) and the controllers' states every 0.5 s, and
// one that carries out the pages' requests (only with `control`), each with
// its own connection to the node.
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

namespace servoloop::view {

class HttpWsServer;
class StaticFiles;

// One request to the node, answered as its IPC answers (an object with
// "ok"). Throws servoloop::Error when the node cannot be reached.
using NodeRequest = std::function<nlohmann::json(const nlohmann::json& request)>;

struct ViewOptions {
  std::string host = "127.0.0.1";  // loopback unless asked
  unsigned port = 8080;            // 0: any free port (port() tells which)
  // The pages may start and stop controllers, engage and release the
  // emergency stop, and pause, step and reset the world.
  bool control = false;
  double frame_rate_hz = 60.0;
  // The page's folder; empty: the one installed with servoloop (or the
  // source tree's view/web for a build tree).
  std::filesystem::path web_dir;
  // Debian's libjs-three.
  std::filesystem::path three_dir = "/usr/share/javascript/three";
};

// "HOST:PORT", "PORT" or ":PORT" into options.host/port. Throws ConfigError
// naming the text and the form.
void parseViewAddress(const std::string& text, ViewOptions& options);

// The page's folder of this servoloop (installed, or in the source tree).
std::filesystem::path defaultWebDirectory();

class ViewServer {
 public:
  // `connect` opens a new connection to the node; it is called once per
  // thread that talks to it, and again after a connection failed.
  ViewServer(ViewOptions options, std::function<NodeRequest()> connect);
  ~ViewServer();  // stop()
  ViewServer(const ViewServer&) = delete;
  ViewServer& operator=(const ViewServer&) = delete;

  // Checks the page's and three.js's folders, binds the address and starts
  // the threads. Throws ConfigError naming what is missing or the address
  // and the fix. Warns (logs) when the address is not loopback.
  void start();
  void stop();  // idempotent

  unsigned port() const;
  std::string url() const;
  // Pages connected now.
  std::size_t pages() const;

 private:
  void opened(std::uint64_t page);
  void closed(std::uint64_t page);
  void message(std::uint64_t page, const std::string& text);
  void frameLoop();
  void commandLoop();
  // One round of the frame thread: a frame (and the scene when it changed,
  // the controllers when due) to every page. Throws Error when the node is gone.
  void sendRound(const NodeRequest& node, bool controllers_due);
  void refreshScene(const NodeRequest& node, const nlohmann::json& frame);
  void sendToAll(const std::string& text);
  void sendTo(std::uint64_t page, const nlohmann::json& message);
  nlohmann::json carryOut(const NodeRequest& node, const nlohmann::json& request);

  ViewOptions options_;
  std::function<NodeRequest()> connect_;
  std::unique_ptr<StaticFiles> files_;
  std::unique_ptr<HttpWsServer> server_;

  mutable std::mutex pages_mutex_;
  std::set<std::uint64_t> pages_;
  std::set<std::uint64_t> new_pages_;  // to be sent the scene
  std::condition_variable pages_changed_;

  std::mutex scene_mutex_;
  std::string scene_text_;  // the scene message, as sent
  std::int64_t scene_generation_ = -1;
  std::vector<std::string> robots_;  // namespaces, for the controllers' states
  std::vector<std::string> warnings_;  // shown to every page

  std::mutex commands_mutex_;
  std::condition_variable commands_changed_;
  std::deque<std::pair<std::uint64_t, nlohmann::json>> commands_;

  // The real-time factor, measured over half a second or more of wall time
  // (the frame thread's).
  double rtf_sim_s_ = -1.0;
  std::chrono::steady_clock::time_point rtf_wall_{};
  double rtf_ = std::nan("");
  std::atomic<bool> controllers_now_{false};  // send the controllers' states in the next round

  std::atomic<bool> stopping_{false};
  std::thread frame_thread_;
  std::thread command_thread_;
  bool started_ = false;
};

}  // namespace servoloop::view
