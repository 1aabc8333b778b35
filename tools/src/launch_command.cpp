// `servoloop launch FILE [options]`: runs a world from a launch file, either
// headless for a --duration of simulated time (then prints the end-of-run
// summary) or until SIGINT/SIGTERM, serving the other commands over IPC.
#include <signal.h>

#include <atomic>
#include <chrono>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "plot_gnuplot.hpp"
#include "progress_bar.hpp"
#include "servoloop/node/launch_file.hpp"
#include "servoloop/node/node.hpp"
#include "servoloop/node/run_summary.hpp"
#include "ros1_bridge_process.hpp"
#include "servoloop/ipc/ipc_client.hpp"
#include "servoloop/view/view_server.hpp"
#include "view_connection.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::cli {
namespace {

namespace node = servoloop::node;
namespace fs = std::filesystem;

struct LaunchOptions {
  std::string file;
  std::vector<std::string> roslaunch_args;  // name:=value, for ROS .launch files
  std::string backend;
  std::optional<double> duration_s;
  std::optional<double> real_time_factor;
  std::string clock;  // "", "sim" or "wall"
  std::vector<std::string> publications;
  std::vector<std::string> recordings;
  std::string plot;
  bool json = false;
  bool ipc = false;
  bool ros1_bridge = false;
  std::vector<std::string> plugin_dirs;
  std::string view;  // [HOST:]PORT of the browser view; empty: none
  bool view_control = false;
};

// The node the signal handler stops. requestShutdown is one atomic store, so
// calling it from a signal handler is safe.
std::atomic<node::Node*> g_running_node{nullptr};

extern "C" void onShutdownSignal(int /*signal*/) {
  if (node::Node* running = g_running_node.load()) running->requestShutdown();
}

class ShutdownSignals {
 public:
  explicit ShutdownSignals(node::Node& running) {
    g_running_node.store(&running);
    struct sigaction action {};
    action.sa_handler = onShutdownSignal;
    sigemptyset(&action.sa_mask);
    // A second Ctrl-C, while the first is being handled, ends the process.
    action.sa_flags = SA_RESETHAND;
    ::sigaction(SIGINT, &action, &previous_int_);
    ::sigaction(SIGTERM, &action, &previous_term_);
  }
  ~ShutdownSignals() {
    ::sigaction(SIGINT, &previous_int_, nullptr);
    ::sigaction(SIGTERM, &previous_term_, nullptr);
    g_running_node.store(nullptr);
  }
  ShutdownSignals(const ShutdownSignals&) = delete;
  ShutdownSignals& operator=(const ShutdownSignals&) = delete;

 private:
  struct sigaction previous_int_ {};
  struct sigaction previous_term_ {};
};

// The launch file with the command line's flags applied on top.
node::LaunchFile launchFileWithFlags(const LaunchOptions& options) {
  std::map<std::string, std::string> roslaunch_args;
  for (const std::string& text : options.roslaunch_args) {
    const auto assign = text.find(":=");
    if (assign == std::string::npos || assign == 0) {
      throw Error("'" + text + "' is not name:=value; launch takes FILE, then name:=value arguments for a ROS "
                  ".launch file, then options");
    }
    roslaunch_args[text.substr(0, assign)] = text.substr(assign + 2);
  }
  node::LaunchFile launch = node::loadLaunchFile(options.file, roslaunch_args);
  for (const std::string& text : options.publications) launch.publish.push_back(node::parsePubFlag(text));
  for (const std::string& text : options.recordings) {
    node::RecordSpec record = node::parseRecordFlag(text);
    // A --record of a topic the file records already replaces the file's entry.
    std::erase_if(launch.record, [&](const node::RecordSpec& r) { return r.topic == record.topic; });
    launch.record.push_back(std::move(record));
  }
  if (!options.plot.empty()) launch.plot = fs::absolute(options.plot).lexically_normal();
  if (!launch.plot.empty() && launch.record.empty()) {
    throw Error("--plot " + launch.plot.string() +
                ": nothing is recorded, so there is nothing to plot; add --record TOPIC=FILE.csv");
  }
  return launch;
}

void plotRecordings(const node::LaunchFile& launch) {
  PlotRequest request;
  request.png = launch.plot;
  for (const node::RecordSpec& record : launch.record) {
    if (fs::exists(record.file) && fs::file_size(record.file) > 0) request.csv_files.push_back(record.file);
  }
  if (request.csv_files.empty()) throw Error("--plot: no recorded topic carried any message; nothing to plot");
  request.title = "servoloop launch " + (launch.source.empty() ? std::string() : launch.source.filename().string());
  plotToPng(request);
}

// The view's connection to this process's own world: its world socket, or
// (when another node serves that) its first robot's.
view::NodeRequest connectToOwnWorld(node::Node& world) {
  try {
    servoloop::ipc::IpcClient client = servoloop::ipc::IpcClient::connectToNode("/");
    const nlohmann::json ping = client.call("ping");
    if (ping.value("robots", std::vector<std::string>{}) == world.robotNamespaces()) {
      return nodeRequestOver(std::move(client));
    }
  } catch (const Error&) {
    // Not served by this node: its robots' sockets below.
  }
  const std::vector<std::string> robots = world.robotNamespaces();
  if (robots.empty()) throw Error("this world's socket is served by another node and it has no robot yet");
  return nodeRequestOver(servoloop::ipc::IpcClient::connectToNode(robots.front()));
}

void runLaunch(const LaunchOptions& options) {
  node::LaunchFile launch = launchFileWithFlags(options);
  if (launch.robots.empty()) {
    logger().warn("{}: no robots: the world starts empty; add 'robots: [{{urdf: FILE}}]' or spawn one into the running "
                  "world with `servoloop spawn-model --urdf FILE --model NAME`",
                  options.file);
  }
  node::NodeOptions node_options;
  node_options.duration_s = options.duration_s;
  node_options.real_time_factor = options.real_time_factor;
  if (!options.backend.empty()) node_options.backend = options.backend;
  if (!options.clock.empty()) node_options.wall_clock = options.clock == "wall";
  // A batch run serves no socket unless asked: it would otherwise collide
  // with an interactive node of the same robot namespace.
  // The view reads the world through the sockets, as `servoloop view` does.
  node_options.serve_ipc = !options.duration_s || options.ipc || !options.view.empty();
  for (const std::string& dir : options.plugin_dirs) node_options.plugin_directories.emplace_back(dir);

  const bool ros1_bridge = launch.ros1_bridge || options.ros1_bridge;
  if (ros1_bridge) {
    if (!node_options.serve_ipc) {
      throw Error("--ros1-bridge: the bridge talks to the node's socket, which a --duration run does not serve; add --ipc");
    }
    ros1BridgeProgram();  // says how to get it, before anything starts
  }

  if (options.view_control && options.view.empty()) {
    throw Error("--view-control: there is no view to control from; add --view [HOST:]PORT");
  }
  // The view is bound before the world is built: a port in use ends the
  // launch at once. Pages that come before the world runs wait for it.
  std::atomic<node::Node*> running_world{nullptr};
  std::unique_ptr<view::ViewServer> view_server;
  if (!options.view.empty()) {
    view::ViewOptions view_options;
    view::parseViewAddress(options.view, view_options);
    view_options.control = options.view_control;
    view_server = std::make_unique<view::ViewServer>(view_options, [&running_world] {
      node::Node* world = running_world.load();
      if (world == nullptr) throw Error("the world is starting");
      return connectToOwnWorld(*world);
    });
    view_server->start();
  }
  node::Node world(launch, node_options);
  // However the launch ends, the view stops before the world goes.
  struct ViewStopper {
    view::ViewServer* view;
    ~ViewStopper() {
      if (view != nullptr) view->stop();
    }
  } view_stopper{view_server.get()};
  {
    ShutdownSignals signals(world);
    world.start();
    running_world.store(&world);
    if (view_server) logger().info("view: open {} in a browser", view_server->url());
    Ros1BridgeProcesses bridges;
    if (ros1_bridge) {
      for (const std::string& ns : world.robotNamespaces()) bridges.start(ns);
    }
    if (!options.duration_s) {
      std::string names;
      for (const std::string& ns : world.robotNamespaces()) names += (names.empty() ? "" : ", ") + ns;
      logger().info("world running (robots: {}; real-time factor {}); stop it with Ctrl-C",
                    names.empty() ? "none yet" : names, world.realTimeFactor());
    }
    std::unique_ptr<ProgressBar> progress;
    // Draws only when stderr is a terminal (ProgressBar checks).
    if (options.duration_s) progress = std::make_unique<ProgressBar>(*options.duration_s);
    const auto wall_start = std::chrono::steady_clock::now();
    world.waitUntilDone([&] {
      if (!progress) return;
      const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
      progress->update(world.simTime(), wall_s);
    });
    if (progress) progress->finish();
    bridges.stop();  // before the node: a bridge whose node vanished would report it
    if (view_server) view_server->stop();
    world.shutdown();
  }

  const node::RunSummary summary = world.summary();
  if (options.json) {
    std::cout << node::toJson(summary).dump() << std::endl;
  } else {
    std::cout << node::toText(summary) << std::flush;
  }
  if (!launch.plot.empty()) {
    plotRecordings(launch);
    logger().info("plot written to {}", launch.plot.string());
  }
  // A batch run is judged by its exit status: what the launch file asked for
  // must have happened.
  bool failed = false;
  for (const node::RobotSummary& robot : summary.robots) {
    if (robot.launch_failures.empty()) continue;
    std::string text;
    for (const std::string& failure : robot.launch_failures) text += (text.empty() ? "" : "; ") + failure;
    logger().error("robot {}: {}{}", robot.robot_namespace, text,
                   options.duration_s ? " (see above); exit status 1" : " (see above)");
    failed = true;
  }
  // So must the robots have run to the end: one stopped for its hardware (a
  // read/write/step error, a NaN joint state from read(), the loop stopped)
  // ended the run with its controllers contained.
  for (const node::RobotSummary& robot : summary.robots) {
    if (!robot.stopped_by_hardware) continue;
    logger().error("robot {}: the run ended with the robot stopped for its hardware: {}{}", robot.robot_namespace,
                   robot.safety_reason.empty() ? robot.safety_state : robot.safety_reason,
                   options.duration_s ? " (see above); exit status 1" : " (see above)");
    failed = true;
  }
  if (options.duration_s && failed) throw CliExit{1};
}

void addLaunchCommand(CLI::App& root) {
  auto options = std::make_shared<LaunchOptions>();
  CLI::App* launch = root.add_subcommand(
      "launch", "Start a world from a launch file: backend, robots, controllers, timed publications, recordings");
  launch->add_option("file", options->file,
                     "Launch file: YAML (robots/one_dof/one_dof_w_jnt_ctl.launch.yaml) or a ROS .launch file")
      ->required()
      ->check(CLI::ExistingFile);
  launch->add_option("args", options->roslaunch_args, "Arguments of a ROS .launch file, as roslaunch takes them")
      ->type_name("NAME:=VALUE");
  launch->add_option("--backend", options->backend, "Simulation backend (bullet, mock, ...); overrides world.backend")
      ->type_name("NAME");
  launch->add_option("--clock", options->clock,
                     "sim: simulated robots run in lockstep with their physics (default); wall: on the wall clock, "
                     "as hardware does (overrides world.clock)")
      ->type_name("sim|wall")
      ->check(CLI::IsMember({"sim", "wall"}));
  launch->add_option("--duration", options->duration_s, "Seconds to run (simulated; wall seconds on the wall clock), then exit with a summary")
      ->type_name("SECONDS")
      ->check(numberWithin(0.0, kMaxDurationS, "simulated seconds"));
  launch->add_option("--rtf", options->real_time_factor,
                     "Real-time factor; 0 = as fast as possible (default 0 with --duration, 1 without)")
      ->type_name("FACTOR")
      ->check(numberWithin(0.0, 1e6, "simulated seconds per wall second; 0 = as fast as possible"));
  launch->add_option("--pub", options->publications,
                     "Publish a message at simulated TIME s (default 0): a number is a std_msgs/Float64, [a, b] a "
                     "Float64MultiArray, {field: ...} the type of its topic or TYPE; repeatable")
      ->type_name("TOPIC[:TYPE]:=VALUE[@TIME]");
  launch->add_option("--record", options->recordings, "Record a topic to CSV; repeatable")->type_name("TOPIC=FILE.csv");
  launch->add_option("--plot", options->plot, "After the run, plot what was recorded to this PNG")->type_name("FILE.png");
  launch->add_flag("--json", options->json, "Print the end-of-run summary as one JSON object");
  launch->add_flag("--ros1-bridge", options->ros1_bridge,
                   "Also start `servoloop ros1-bridge` for each robot (as `ros1_bridge: true` in the launch file)");
  launch->add_flag("--ipc", options->ipc,
                   "Serve the IPC sockets during a --duration run too (runs without --duration always do)");
  launch->add_option("--plugin-dir", options->plugin_dirs,
                     "Search this directory for plugins first (repeatable); SERVOLOOP_PLUGIN_PATH and the "
                     "installation's plugin folder follow")
      ->type_name("DIR");
  launch->add_option("--view", options->view,
                     "Serve a live 3D view of the world to a browser on [HOST:]PORT (loopback unless a host is "
                     "given); see docs/view.md")
      ->type_name("[HOST:]PORT");
  addViewControlFlag(*launch, options->view_control);
  launch->callback([options] { runLaunch(*options); });
}

}  // namespace
}  // namespace servoloop::cli

SERVOLOOP_CLI_COMMANDS(10, servoloop::cli::addLaunchCommand)
