#include "servoloop/view/view_server.hpp"

#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "http_ws_server.hpp"
#include "scene_builder.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "static_files.hpp"

namespace servoloop::view {

using nlohmann::json;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

constexpr auto kControllersPeriod = std::chrono::milliseconds(500);
constexpr auto kReconnectPeriod = std::chrono::milliseconds(500);

// The node's reply, or Error carrying its "error" text.
json ok(const json& reply, const std::string& op) {
  if (reply.is_object() && reply.value("ok", false)) return reply;
  const std::string why = reply.is_object() && reply.contains("error") && reply["error"].is_string()
                              ? reply["error"].get<std::string>()
                              : "no reply";
  throw Error(op + ": " + why);
}

bool loopback(const std::string& host) { return host == "127.0.0.1" || host == "::1" || host.rfind("127.", 0) == 0; }

}  // namespace

void parseViewAddress(const std::string& text, ViewOptions& options) {
  const std::string form = "give PORT, :PORT or HOST:PORT with a port from 0 to 65535 (e.g. --view 8080 or --view 127.0.0.1:8080)";
  std::string host = options.host;
  std::string port = text;
  if (const auto colon = text.rfind(':'); colon != std::string::npos) {
    host = text.substr(0, colon);
    port = text.substr(colon + 1);
    if (host.size() >= 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
    if (host.empty()) host = options.host;
  }
  if (port.empty() || port.size() > 5 || port.find_first_not_of("0123456789") != std::string::npos ||
      std::stoul(port) > 65535) {
    throw ConfigError("view address '" + text + "': " + form);
  }
  options.host = host == "localhost" ? "127.0.0.1" : host;
  options.port = static_cast<unsigned>(std::stoul(port));
}

fs::path defaultWebDirectory() {
  std::error_code error;
  const fs::path executable = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    const fs::path installed = executable.parent_path().parent_path() / "share" / "servoloop" / "view";
    if (fs::is_regular_file(installed / "index.html", error)) return installed;
  }
  return fs::path(SERVOLOOP_VIEW_SOURCE_DIR);
}

ViewServer::ViewServer(ViewOptions options, std::function<NodeRequest()> connect)
    : options_(std::move(options)), connect_(std::move(connect)), files_(std::make_unique<StaticFiles>()) {
  if (options_.web_dir.empty()) options_.web_dir = defaultWebDirectory();
  if (!(options_.frame_rate_hz > 0.0) || !std::isfinite(options_.frame_rate_hz)) {
    throw ConfigError("view: the frame rate must be a number > 0");
  }
}

ViewServer::~ViewServer() { stop(); }

void ViewServer::start() {
  if (started_) return;
  std::error_code error;
  if (!fs::is_regular_file(options_.web_dir / "index.html", error)) {
    throw ConfigError("view: the page is not in '" + options_.web_dir.string() +
                      "' (no index.html); reinstall servoloop or build it again");
  }
  if (!fs::is_regular_file(options_.three_dir / "build" / "three.min.js", error)) {
    throw ConfigError("view: three.js is not in '" + options_.three_dir.string() +
                      "'; install Debian's libjs-three (apt install libjs-three)");
  }
  files_->addFolder("/", options_.web_dir);
  files_->addFolder("/three/", options_.three_dir);
  HttpWsServer::Handlers handlers;
  handlers.http = [this](const std::string& path) { return files_->get(path); };
  handlers.opened = [this](std::uint64_t page) { opened(page); };
  handlers.closed = [this](std::uint64_t page) { closed(page); };
  handlers.message = [this](std::uint64_t page, const std::string& text) { message(page, text); };
  server_ = std::make_unique<HttpWsServer>(std::move(handlers), "/ws");
  server_->start(options_.host, options_.port);
  if (!loopback(options_.host)) {
    logger().warn("view: serving on {} — every machine that reaches this address can watch{}; use 127.0.0.1 to keep "
                  "it on this machine",
                  options_.host, options_.control ? " and control the robots" : "");
  }
  started_ = true;
  stopping_ = false;
  frame_thread_ = std::thread([this] { frameLoop(); });
  if (options_.control) command_thread_ = std::thread([this] { commandLoop(); });
}

void ViewServer::stop() {
  if (!started_) return;
  started_ = false;
  stopping_ = true;
  pages_changed_.notify_all();
  commands_changed_.notify_all();
  if (frame_thread_.joinable()) frame_thread_.join();
  if (command_thread_.joinable()) command_thread_.join();
  server_->stop();
}

unsigned ViewServer::port() const { return server_ ? server_->port() : options_.port; }

std::string ViewServer::url() const {
  const std::string host = options_.host.find(':') != std::string::npos ? "[" + options_.host + "]" : options_.host;
  return fmt::format("http://{}:{}/", host == "0.0.0.0" ? "127.0.0.1" : host, port());
}

std::size_t ViewServer::pages() const {
  std::lock_guard lock(pages_mutex_);
  return pages_.size();
}

void ViewServer::opened(std::uint64_t page) {
  sendTo(page, {{"type", "hello"}, {"control", options_.control}, {"version", 1}});
  {
    std::lock_guard lock(pages_mutex_);
    pages_.insert(page);
    new_pages_.insert(page);
  }
  pages_changed_.notify_all();
}

void ViewServer::closed(std::uint64_t page) {
  std::lock_guard lock(pages_mutex_);
  pages_.erase(page);
  new_pages_.erase(page);
}

void ViewServer::message(std::uint64_t page, const std::string& text) {
  json request = json::parse(text, nullptr, false);
  const json id = request.is_object() && request.contains("id") ? request["id"] : json(nullptr);
  if (!request.is_object() || !request.contains("op") || !request["op"].is_string()) {
    sendTo(page, {{"type", "reply"}, {"id", id}, {"ok", false}, {"error", "a request is an object with an \"op\""}});
    return;
  }
  if (!options_.control) {
    sendTo(page, {{"type", "reply"},
                  {"id", id},
                  {"ok", false},
                  {"error", "this view is read-only; start it with --view-control to control the robots"}});
    return;
  }
  {
    std::lock_guard lock(commands_mutex_);
    if (commands_.size() >= 64) {
      sendTo(page, {{"type", "reply"}, {"id", id}, {"ok", false}, {"error", "too many requests waiting; try again"}});
      return;
    }
    commands_.emplace_back(page, std::move(request));
  }
  commands_changed_.notify_one();
}

void ViewServer::sendTo(std::uint64_t page, const json& message) {
  if (server_) server_->send(page, message.dump(-1, ' ', false, json::error_handler_t::replace));
}

void ViewServer::sendToAll(const std::string& text) {
  std::vector<std::uint64_t> pages;
  {
    std::lock_guard lock(pages_mutex_);
    pages.assign(pages_.begin(), pages_.end());
  }
  for (std::uint64_t page : pages) server_->send(page, text, 1u << 20);
}

void ViewServer::refreshScene(const NodeRequest& node, const json& frame) {
  const json scene = ok(node({{"op", "view.scene"}}), "view.scene");
  std::vector<SceneModel> models;
  std::vector<std::string> robots;
  std::vector<std::string> warnings;
  for (const json& model : scene.at("models")) {
    SceneModel entry{model.value("name", ""), model.value("ns", ""), model.value("urdf", ""), model.value("path", ""), {}};
    robots.push_back(entry.ns);  // its controllers are shown either way
    if (!model.value("simulated", true)) {
      // Its joints move on its own loop's thread, which the world's
      // snapshots do not reach.
      warnings.push_back("robot '" + entry.ns +
                         "' runs on the wall clock (hardware): the view draws the simulated world only");
      continue;
    }
    for (const json& in_frame : frame.at("models")) {
      if (in_frame.value("ns", "") == entry.ns) entry.joint_names = in_frame.value("joint_names", std::vector<std::string>{});
    }
    models.push_back(std::move(entry));
  }
  json message = buildScene(models, scene.value("ground_plane", false), *files_, warnings);
  message["generation"] = frame.at("generation");
  for (const std::string& warning : warnings) logger().warn("view: {}", warning);
  std::lock_guard lock(scene_mutex_);
  scene_text_ = message.dump(-1, ' ', false, json::error_handler_t::replace);
  scene_generation_ = frame.at("generation").get<std::int64_t>();
  robots_ = std::move(robots);
  warnings_ = std::move(warnings);
  // Every page gets the new scene, with its warnings.
  std::lock_guard pages_lock(pages_mutex_);
  new_pages_ = pages_;
}

void ViewServer::sendRound(const NodeRequest& node, bool controllers_due) {
  const json frame = ok(node({{"op", "view.frame"}}), "view.frame");
  std::int64_t generation = frame.at("generation").get<std::int64_t>();
  bool scene_changed = false;
  {
    std::lock_guard lock(scene_mutex_);
    scene_changed = generation != scene_generation_;
  }
  if (scene_changed) refreshScene(node, frame);

  // Pages new since the last round (or all, after a scene change) get the scene first.
  std::vector<std::uint64_t> fresh;
  {
    std::lock_guard lock(pages_mutex_);
    fresh.assign(new_pages_.begin(), new_pages_.end());
    new_pages_.clear();
  }
  if (!fresh.empty()) {
    std::string scene;
    std::vector<std::string> warnings;
    {
      std::lock_guard lock(scene_mutex_);
      scene = scene_text_;
      warnings = warnings_;
    }
    for (std::uint64_t page : fresh) {
      server_->send(page, scene, 64u << 20);
      for (const std::string& warning : warnings) sendTo(page, {{"type", "warning"}, {"text", warning}});
    }
    controllers_due = true;
  }

  // The real-time factor over the last half second or more of wall time.
  const double sim_time = frame.value("sim_time", 0.0);
  const Clock::time_point now = Clock::now();
  if (rtf_sim_s_ < 0.0 || sim_time < rtf_sim_s_) {
    rtf_sim_s_ = sim_time;
    rtf_wall_ = now;
  } else if (now - rtf_wall_ >= std::chrono::milliseconds(500)) {
    rtf_ = (sim_time - rtf_sim_s_) / std::chrono::duration<double>(now - rtf_wall_).count();
    rtf_sim_s_ = sim_time;
    rtf_wall_ = now;
  }
  const double rtf = rtf_;
  json models = json::array();
  for (const json& model : frame.at("models")) {
    models.push_back({{"ns", model.at("ns")}, {"pose", model.at("pose")}, {"q", model.at("q")}});
  }
  const json message = {{"type", "frame"},
                        {"generation", generation},
                        {"t", sim_time},
                        {"rtf", std::isfinite(rtf) ? json(rtf) : json(nullptr)},
                        {"paused", frame.value("paused", false)},
                        {"steps", frame.value("steps", 0)},
                        {"models", std::move(models)}};
  const std::string text = message.dump();
  std::vector<std::uint64_t> pages;
  {
    std::lock_guard lock(pages_mutex_);
    pages.assign(pages_.begin(), pages_.end());
  }
  // A page that has not taken the last megabyte skips this frame.
  for (std::uint64_t page : pages) server_->send(page, text, 1u << 20);

  if (!controllers_due) return;
  std::vector<std::string> robots;
  {
    std::lock_guard lock(scene_mutex_);
    robots = robots_;
  }
  json states = json::array();
  for (const std::string& ns : robots) {
    json entry = {{"ns", ns}};
    const json list = node({{"op", "control.list"}, {"robot", ns}});
    json controllers = json::array();
    if (list.value("ok", false)) {
      for (const json& controller : list.at("controllers")) {
        controllers.push_back(
            {{"name", controller.at("name")}, {"type", controller.at("type")}, {"state", controller.at("state")}});
      }
    }
    entry["controllers"] = std::move(controllers);
    const json safety = node({{"op", "control.safety"}, {"robot", ns}});
    if (safety.value("ok", false)) {
      entry["estop"] = safety.value("emergency_stop", false);
      entry["safety"] = safety.value("state", "");
    }
    states.push_back(std::move(entry));
  }
  sendToAll(json{{"type", "controllers"}, {"robots", std::move(states)}}.dump());
}

void ViewServer::frameLoop() {
  NodeRequest node;
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / options_.frame_rate_hz));
  Clock::time_point next = Clock::now();
  Clock::time_point next_controllers = next;
  std::string last_failure;
  while (!stopping_) {
    {
      std::unique_lock lock(pages_mutex_);
      if (pages_.empty()) {
        pages_changed_.wait_for(lock, std::chrono::milliseconds(200), [&] { return stopping_ || !pages_.empty(); });
        next = Clock::now();
        continue;
      }
    }
    try {
      if (!node) node = connect_();
      const bool controllers_due = Clock::now() >= next_controllers || controllers_now_.exchange(false);
      if (controllers_due) next_controllers = Clock::now() + kControllersPeriod;
      sendRound(node, controllers_due);
      last_failure.clear();
    } catch (const std::exception& error) {
      node = nullptr;
      if (error.what() != last_failure) {
        last_failure = error.what();
        logger().warn("view: {}", last_failure);
        sendToAll(json{{"type", "warning"}, {"text", "the node does not answer: " + last_failure}}.dump());
      }
      std::unique_lock lock(pages_mutex_);
      pages_changed_.wait_for(lock, kReconnectPeriod, [&] { return stopping_.load(); });
      next = Clock::now();
      continue;
    }
    next += period;
    const Clock::time_point now = Clock::now();
    if (next < now) next = now;  // behind: no burst to catch up
    std::unique_lock lock(pages_mutex_);
    pages_changed_.wait_until(lock, next, [&] { return stopping_.load(); });
  }
}

json ViewServer::carryOut(const NodeRequest& node, const json& request) {
  const std::string op = request.at("op").get<std::string>();
  auto text = [&](const char* field) {
    if (!request.contains(field) || !request[field].is_string()) throw Error(fmt::format("'{}' needs a string '{}'", op, field));
    return request[field].get<std::string>();
  };
  auto names = [&](const char* field) {
    std::vector<std::string> list;
    if (!request.contains(field)) return list;
    if (!request[field].is_array()) throw Error(fmt::format("'{}': '{}' must be a list of names", op, field));
    for (const json& name : request[field]) {
      if (!name.is_string()) throw Error(fmt::format("'{}': '{}' must be a list of names", op, field));
      list.push_back(name.get<std::string>());
    }
    return list;
  };
  json forward;
  if (op == "switch") {
    forward = {{"op", "control.switch"}, {"robot", text("ns")}, {"start", names("start")}, {"stop", names("stop")},
               {"strictness", "strict"}};
  } else if (op == "estop") {
    if (!request.contains("engaged") || !request["engaged"].is_boolean()) throw Error("'estop' needs 'engaged': true or false");
    forward = {{"op", "control.estop"}, {"robot", text("ns")}, {"engage", request["engaged"].get<bool>()}};
  } else if (op == "pause" || op == "unpause" || op == "reset") {
    forward = {{"op", "world." + op}};
  } else if (op == "step") {
    const json steps = request.value("steps", json(1));
    if (!steps.is_number_unsigned() || steps.get<std::uint64_t>() < 1) throw Error("'step' needs 'steps': a whole number >= 1");
    forward = {{"op", "world.step"}, {"steps", steps}};
  } else {
    throw Error("unknown request '" + op + "'; the page sends switch, estop, pause, unpause, step or reset");
  }
  return ok(node(forward), forward["op"].get<std::string>());
}

void ViewServer::commandLoop() {
  NodeRequest node;
  while (true) {
    std::pair<std::uint64_t, json> command;
    {
      std::unique_lock lock(commands_mutex_);
      commands_changed_.wait(lock, [&] { return stopping_ || !commands_.empty(); });
      if (stopping_) return;
      command = std::move(commands_.front());
      commands_.pop_front();
    }
    const json id = command.second.contains("id") ? command.second["id"] : json(nullptr);
    json reply = {{"type", "reply"}, {"id", id}};
    try {
      if (!node) node = connect_();
      carryOut(node, command.second);
      reply["ok"] = true;
    } catch (const std::exception& error) {
      reply["ok"] = false;
      reply["error"] = error.what();
      node = nullptr;  // connected again for the next one, in case this one broke
    }
    sendTo(command.first, reply);
    controllers_now_ = true;  // the pages see what the request changed at once
  }
}

}  // namespace servoloop::view
