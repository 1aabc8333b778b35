// `servoloop control list|list-joints|load|unload|start|stop|switch|reload-libraries|gains`:
// the controller manager commands that talk to a running node (ros_control's
// `controller_manager` script), and the safety commands `control safety|estop|recover`.
// `control list-types` lives in control_command.cpp.
#include <algorithm>
#include <array>
#include <optional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <fmt/format.h>

#include "command_registry.hpp"
#include "node_connection.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::cli {
namespace {


// A switch is carried out by the real-time thread at its next cycle.
constexpr double kSwitchCallTimeoutS = 30.0;

struct ControlOptions {
  std::string ns;
  bool json = false;
  std::vector<std::string> names;
  std::vector<std::string> start;
  std::vector<std::string> stop;
  std::string strictness = "strict";
  bool start_asap = false;
  double timeout_s = 0.0;
  bool force_kill = false;
  std::string estop;  // "on" or "off"
  bool reset = false;
  // control gains: the controller, the PID, and each gain given (nullopt: keep it).
  std::string controller;
  std::string pid;
  std::array<std::optional<double>, 5> gains;  // p, i, d, i_clamp_min, i_clamp_max
  std::optional<bool> antiwindup;
};

// `control gains`' options, in the order of ControlOptions::gains.
constexpr std::array<const char*, 5> kGainOptionKeys = {"p", "i", "d", "i_clamp_min", "i_clamp_max"};

std::string stringField(const nlohmann::json& object, const char* key) {
  const auto found = object.find(key);
  return found != object.end() && found->is_string() ? found->get<std::string>() : "";
}

// controller_manager list's layout: "name - type ( state )", then each claimed
// interface with its resources.
void printControllers(const nlohmann::json& controllers) {
  for (const auto& controller : controllers) {
    std::cout << stringField(controller, "name") << " - " << stringField(controller, "type")
              << " ( " << stringField(controller, "state") << " )\n";
    const auto claims = controller.find("claimed_resources");
    if (claims == controller.end() || !claims->is_array()) continue;
    for (const auto& claim : *claims) {
      std::cout << "    " << stringField(claim, "hardware_interface") << ":";
      const auto resources = claim.value("resources", nlohmann::json::array());
      if (resources.empty()) std::cout << " (no resources)";
      for (const auto& resource : resources) {
        std::cout << " " << (resource.is_string() ? resource.get<std::string>() : resource.dump());
      }
      std::cout << "\n";
    }
  }
}

void runList(const ControlOptions& options) {
  servoloop::ipc::IpcClient client = connectToRobotNode(options.ns);
  const auto reply = client.call("control.list");
  const auto controllers = reply.value("controllers", nlohmann::json::array());
  if (options.json) {
    std::cout << controllers.dump(2) << "\n";
  } else {
    printControllers(controllers);
  }
}

void runListJoints(const ControlOptions& options) {
  servoloop::ipc::IpcClient client = connectToRobotNode(options.ns);
  const auto reply = client.call("control.list_joints");
  const auto joints = reply.value("joints", nlohmann::json::array());
  if (options.json) {
    std::cout << joints.dump(2) << "\n";
    return;
  }
  for (const auto& joint : joints) {
    std::cout << stringField(joint, "name") << ":";
    std::string separator = " ";
    for (const auto& interface : joint.value("interfaces", nlohmann::json::array())) {
      std::cout << separator << (interface.is_string() ? interface.get<std::string>() : "?");
      separator = ", ";
    }
    std::cout << "\n";
  }
}

// load/unload each name in order; the first failure ends the command.
void runEach(const ControlOptions& options, const char* op, const char* done) {
  servoloop::ipc::IpcClient client = connectToRobotNode(options.ns);
  for (const auto& name : options.names) {
    client.call(op, {{"name", name}});
    std::cout << done << " '" << name << "'\n";
  }
}

void runSwitch(const ControlOptions& options) {
  if (options.start.empty() && options.stop.empty()) {
    throw Error("nothing to switch: give --start and/or --stop controller names");
  }
  servoloop::ipc::IpcClient client = connectToRobotNode(options.ns);
  client.call("control.switch",
              {{"start", options.start},
               {"stop", options.stop},
               {"strictness", options.strictness},
               {"start_asap", options.start_asap},
               {"timeout", options.timeout_s}},
              kSwitchCallTimeoutS + std::max(options.timeout_s, 0.0));
  if (!options.stop.empty()) {
    std::cout << "Stopped:";
    for (const auto& name : options.stop) std::cout << " " << name;
    std::cout << "\n";
  }
  if (!options.start.empty()) {
    std::cout << "Started:";
    for (const auto& name : options.start) std::cout << " " << name;
    std::cout << "\n";
  }
}

void runReloadLibraries(const ControlOptions& options) {
  servoloop::ipc::IpcClient client = connectToRobotNode(options.ns);
  client.call("control.reload_libraries", {{"force_kill", options.force_kill}},
              kSwitchCallTimeoutS);
  std::cout << "Reloaded controller libraries\n";
}

// "state: emergency_stop", then why, as `control safety` prints it.
void printSafety(const nlohmann::json& safety, bool json) {
  if (json) {
    std::cout << safety.dump(2) << "\n";
    return;
  }
  std::cout << "state: " << stringField(safety, "state") << "\n";
  const std::string reason = stringField(safety, "reason");
  if (!reason.empty()) std::cout << reason << "\n";
}

void runSafety(const ControlOptions& options) {
  servoloop::ipc::IpcClient client = connectToRobotNode(options.ns);
  printSafety(client.call("control.safety"), options.json);
}

void runEstop(const ControlOptions& options) {
  servoloop::ipc::IpcClient client = connectToRobotNode(options.ns);
  printSafety(client.call("control.estop", {{"engage", options.estop == "on"}}), options.json);
}

void runRecover(const ControlOptions& options) {
  servoloop::ipc::IpcClient client = connectToRobotNode(options.ns);
  printSafety(client.call("control.recover", nlohmann::json::object(), kSwitchCallTimeoutS), options.json);
}

// One row of `control stats`: a duration's count and figures in microseconds.
void printDurationRow(const std::string& label, const nlohmann::json& d) {
  const auto us = [&](const char* key) { return d.value(key, 0.0) * 1e6; };
  const std::uint64_t count = d.value("count", std::uint64_t{0});
  if (count == 0) {
    std::cout << fmt::format("{:<34} {:>9}\n", label, "-");
    return;
  }
  std::cout << fmt::format("{:<34} {:>9} {:>9.1f} {:>9.1f} {:>9.1f} {:>9.1f} {:>9.1f}\n", label, count, us("min"),
                           us("mean"), us("p50"), us("p99"), us("max"));
}

void runStats(const ControlOptions& options) {
  servoloop::ipc::IpcClient client = connectToRobotNode(options.ns);
  const nlohmann::json reply = client.call("control.stats", {{"reset", options.reset}});
  if (options.json) {
    std::cout << reply.dump(2) << "\n";
  } else {
    const nlohmann::json loop = reply.value("loop", nlohmann::json::object());
    std::cout << fmt::format("{} cycles, {} overruns ({} deadlines skipped), {} hardware errors, real-time factor "
                             "{:.3f}\n",
                             loop.value("cycles", 0), loop.value("overruns", 0), loop.value("skipped_deadlines", 0),
                             loop.value("hardware_errors", 0), loop.value("real_time_factor", 0.0));
    std::cout << fmt::format("{:<34} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}\n", "(us)", "count", "min", "mean", "p50",
                             "p99", "max");
    nlohmann::json cycle = loop.value("compute", nlohmann::json::object());
    cycle["count"] = cycle.value("timed_cycles", 0);
    printDurationRow("cycle", cycle);
    printDurationRow("read()", loop.value("read", nlohmann::json::object()));
    for (const auto& controller : reply.value("controllers", nlohmann::json::array())) {
      printDurationRow(stringField(controller, "name") + " update()", controller.value("update", nlohmann::json::object()));
    }
    printDurationRow("write()", loop.value("write", nlohmann::json::object()));
    printDurationRow("wake-up latency", loop.value("wakeup_latency", nlohmann::json::object()));
    printDurationRow("period jitter", loop.value("period_jitter", nlohmann::json::object()));
  }
  if (options.reset) std::cerr << "statistics reset\n";
}

void runGains(const ControlOptions& options) {
  servoloop::ipc::IpcClient client = connectToRobotNode(options.ns);
  nlohmann::json request = {{"controller", options.controller}};
  if (!options.pid.empty()) request["pid"] = options.pid;
  for (std::size_t k = 0; k < kGainOptionKeys.size(); ++k) {
    if (options.gains[k]) request[kGainOptionKeys[k]] = *options.gains[k];
  }
  if (options.antiwindup) request["antiwindup"] = *options.antiwindup;
  const nlohmann::json reply = client.call("control.gains", request);
  const nlohmann::json pids = reply.value("pids", nlohmann::json::array());
  if (options.json) {
    std::cout << pids.dump(2) << "\n";
    return;
  }
  if (pids.empty()) std::cout << options.controller << " has no PID whose gains can be changed\n";
  for (const auto& pid : pids) {
    std::cout << fmt::format("{}/{}: p {} i {} d {} i_clamp_min {} i_clamp_max {} antiwindup {}\n",
                             options.controller, stringField(pid, "name"), pid.value("p", 0.0), pid.value("i", 0.0),
                             pid.value("d", 0.0), pid.value("i_clamp_min", 0.0), pid.value("i_clamp_max", 0.0),
                             pid.value("antiwindup", false));
  }
}

CLI::App* addClientSubcommand(CLI::App& control, const std::string& name,
                              const std::string& description, ControlOptions& options) {
  CLI::App* command = control.add_subcommand(name, description);
  addNamespaceOption(*command, options.ns);
  return command;
}

void addSwitchTimingOptions(CLI::App& command, ControlOptions& options) {
  command.add_flag("--start-asap", options.start_asap,
                   "Start the controllers as soon as their resources are ready");
  command
      .add_option("--timeout", options.timeout_s,
                  "Seconds the node may wait for the switch to be carried out (0 = no limit)")
      ->type_name("SECONDS")
      ->check(numberWithin(0.0, kMaxDurationS, "seconds; 0 = no limit"));
}

void addControlClientCommands(CLI::App& root) {
  CLI::App& control = commandGroup(
      root, "control", "Controller manager: list, load, start, stop and switch controllers");

  {
    auto options = std::make_shared<ControlOptions>();
    CLI::App* list = addClientSubcommand(
        control, "list", "List the loaded controllers: type, state and claimed resources",
        *options);
    list->add_flag("--json", options->json,
                   "Print a JSON array of {name, type, state, claimed_resources}");
    list->callback([options] { runList(*options); });
  }
  {
    auto options = std::make_shared<ControlOptions>();
    CLI::App* list_joints = addClientSubcommand(
        control, "list-joints", "List the robot's joints and the interfaces each offers",
        *options);
    list_joints->add_flag("--json", options->json, "Print a JSON array of {name, interfaces}");
    list_joints->callback([options] { runListJoints(*options); });
  }
  {
    auto options = std::make_shared<ControlOptions>();
    CLI::App* load = addClientSubcommand(
        control, "load", "Load controllers (configured under <namespace>/<name>/type)", *options);
    load->add_option("names", options->names, "Controller names")->required()->type_name("NAME");
    load->callback([options] { runEach(*options, "control.load", "Loaded"); });
  }
  {
    auto options = std::make_shared<ControlOptions>();
    CLI::App* unload =
        addClientSubcommand(control, "unload", "Unload stopped controllers", *options);
    unload->add_option("names", options->names, "Controller names")->required()->type_name("NAME");
    unload->callback([options] { runEach(*options, "control.unload", "Unloaded"); });
  }
  {
    auto options = std::make_shared<ControlOptions>();
    CLI::App* start = addClientSubcommand(
        control, "start", "Start controllers (one STRICT switch)", *options);
    start->add_option("names", options->start, "Controller names")->required()->type_name("NAME");
    addSwitchTimingOptions(*start, *options);
    start->callback([options] { runSwitch(*options); });
  }
  {
    auto options = std::make_shared<ControlOptions>();
    CLI::App* stop =
        addClientSubcommand(control, "stop", "Stop controllers (one STRICT switch)", *options);
    stop->add_option("names", options->stop, "Controller names")->required()->type_name("NAME");
    addSwitchTimingOptions(*stop, *options);
    stop->callback([options] { runSwitch(*options); });
  }
  {
    auto options = std::make_shared<ControlOptions>();
    CLI::App* switch_command = addClientSubcommand(
        control, "switch", "Stop some controllers and start others in one switch", *options);
    switch_command->add_option("--start", options->start, "Controllers to start")
        ->type_name("NAME");
    switch_command->add_option("--stop", options->stop, "Controllers to stop")->type_name("NAME");
    switch_command
        ->add_option("--strictness", options->strictness,
                     "strict: fail on any unknown/misplaced name; best_effort: drop those")
        ->check(CLI::IsMember({"strict", "best_effort"}))
        ->capture_default_str();
    addSwitchTimingOptions(*switch_command, *options);
    switch_command->callback([options] { runSwitch(*options); });
  }
  {
    auto options = std::make_shared<ControlOptions>();
    CLI::App* reload = addClientSubcommand(
        control, "reload-libraries",
        "Reload the controller plugin libraries (refused while controllers are loaded)",
        *options);
    reload->add_flag("--force-kill", options->force_kill,
                     "Stop and unload every controller first");
    reload->callback([options] { runReloadLibraries(*options); });
  }
  {
    auto options = std::make_shared<ControlOptions>();
    CLI::App* stats = addClientSubcommand(
        control, "stats",
        "Loop statistics: cycle, read(), each controller's update(), write(), wake-up latency and period jitter "
        "(count, min, mean, p50, p99, max), overruns, hardware errors",
        *options);
    stats->add_flag("--json", options->json, "Print the figures as JSON (seconds)");
    stats->add_flag("--reset", options->reset, "Zero the figures after printing them");
    stats->callback([options] { runStats(*options); });
  }
  {
    auto options = std::make_shared<ControlOptions>();
    CLI::App* gains = addClientSubcommand(
        control, "gains",
        "Show a controller's PID gains, or change them while it runs (taken at its next update; ros_control's "
        "dynamic_reconfigure of <controller>/pid)",
        *options);
    gains->add_option("controller", options->controller, "Controller name")->required()->type_name("NAME");
    gains->add_option("--pid", options->pid,
                      "Which PID: pid, <joint>/pid or gains/<joint> (needed when the controller has several)")
        ->type_name("NAME");
    const std::array<const char*, 5> flags = {"--p", "--i", "--d", "--i-clamp-min", "--i-clamp-max"};
    const std::array<const char*, 5> meanings = {"Proportional gain", "Integral gain", "Derivative gain",
                                                 "Lower bound of the integral term (<= 0)",
                                                 "Upper bound of the integral term (>= 0)"};
    for (std::size_t k = 0; k < flags.size(); ++k) {
      gains->add_option(flags[k], options->gains[k], meanings[k])
          ->type_name("X")
          ->check(numberWithin(-1e12, 1e12, "a finite gain"));
    }
    gains->add_option("--antiwindup", options->antiwindup, "Keep the integral inside the clamp (true or false)")
        ->type_name("BOOL");
    gains->add_flag("--json", options->json, "Print the PIDs' gains as JSON");
    gains->callback([options] { runGains(*options); });
  }
  {
    auto options = std::make_shared<ControlOptions>();
    CLI::App* safety = addClientSubcommand(
        control, "safety", "Show the robot's safety state (running, protective_stop, emergency_stop, fault) and why",
        *options);
    safety->add_flag("--json", options->json, "Print {state, emergency_stop, reason, ...} as JSON");
    safety->callback([options] { runSafety(*options); });
  }
  {
    auto options = std::make_shared<ControlOptions>();
    CLI::App* estop = addClientSubcommand(
        control, "estop",
        "Engage (on) or release (off) the emergency stop: effort and velocity commands 0, position commands hold",
        *options);
    estop->add_option("state", options->estop, "on or off")
        ->required()
        ->check(CLI::IsMember({"on", "off"}))
        ->type_name("on|off");
    estop->add_flag("--json", options->json, "Print the safety state after it as JSON");
    estop->callback([options] { runEstop(*options); });
  }
  {
    auto options = std::make_shared<ControlOptions>();
    CLI::App* recover = addClientSubcommand(
        control, "recover",
        "Leave a protective stop or fault: run the loop again and restart the controllers the stop stopped",
        *options);
    recover->add_flag("--json", options->json, "Print the safety state after it as JSON");
    recover->callback([options] { runRecover(*options); });
  }
}

}  // namespace
}  // namespace servoloop::cli

SERVOLOOP_CLI_COMMANDS(31, servoloop::cli::addControlClientCommands)
