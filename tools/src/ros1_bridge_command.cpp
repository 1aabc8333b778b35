// `servoloop ros1-bridge [-N NS] [--no-sim-time] [--print-env]`: runs the ROS 1
// bridge (servoloop_ros1_bridge, beside this executable) against a running
// node. The bridge is built only where Debian's ROS 1 packages are installed;
// without it this command says how to get it. docs/ros1.md.
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command_registry.hpp"
#include "ros1_bridge_process.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::cli {
namespace {

namespace fs = std::filesystem;

struct BridgeOptions {
  std::string ns;
  bool no_sim_time = false;
  bool print_env = false;
  bool no_gazebo_services = false;
};

void runBridge(const BridgeOptions& options) {
  if (options.print_env) {
    const fs::path python = ros1PythonPath();
    // rostopic, rosservice and rosbag read the message packages Debian lacks
    // (control_msgs, controller_manager_msgs) from here.
    std::cout << "export PYTHONPATH=\"" << python.string() << "${PYTHONPATH:+:$PYTHONPATH}\"\n";
    return;
  }
  const fs::path bridge = ros1BridgeProgram();
  std::vector<std::string> args = {bridge.string()};
  if (!options.ns.empty()) args.insert(args.end(), {"--namespace", options.ns});
  if (options.no_sim_time) args.emplace_back("--no-sim-time");
  if (options.no_gazebo_services) args.emplace_back("--no-gazebo-services");
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  ::execv(bridge.c_str(), argv.data());
  throw Error("cannot run " + bridge.string() + ": " + std::strerror(errno));
}

void addRos1BridgeCommand(CLI::App& root) {
  auto options = std::make_shared<BridgeOptions>();
  CLI::App* bridge = root.add_subcommand(
      "ros1-bridge", "Show a running node to ROS 1: topics both ways, /clock, parameters, controller_manager services");
  bridge->add_option("-N,--namespace", options->ns,
                     "Robot namespace of the node to bridge, e.g. /one_DOF_robot (default: the only running node)")
      ->type_name("NS");
  bridge->add_flag("--no-sim-time", options->no_sim_time, "Leave /use_sim_time false");
  bridge->add_flag("--no-gazebo-services", options->no_gazebo_services,
                   "Do not serve Gazebo's /gazebo/* services (model state, spawn and delete, pause, reset, joint "
                   "efforts and properties)");
  bridge->add_flag("--print-env", options->print_env,
                   "Print the PYTHONPATH that lets rostopic and rosservice read control_msgs and "
                   "controller_manager_msgs (eval \"$(servoloop ros1-bridge --print-env)\")");
  bridge->callback([options] { runBridge(*options); });
}

}  // namespace
}  // namespace servoloop::cli

SERVOLOOP_CLI_COMMANDS(74, servoloop::cli::addRos1BridgeCommand)
