// `servoloop world state|pause|unpause|step [N]|reset`: Gazebo's physics
// controls (pause_physics, unpause_physics, the step button,
// reset_simulation) for the world served on default.sock (or the only node).
#include <cstdint>
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "node_connection.hpp"

namespace servoloop::cli {
namespace {

// A step of many cycles or a reset waits for the world's loop.
constexpr double kWorldCallTimeoutS = 600.0;
constexpr std::uint64_t kMaxSteps = 1'000'000'000;

void printState(const nlohmann::json& state) {
  std::cout << fmt::format("{} at t = {} s ({} physics steps)\n",
                           state.value("paused", false) ? "paused" : "running", state.value("sim_time", 0.0),
                           state.value("steps", std::uint64_t{0}));
}

void callWorld(const std::string& op, const nlohmann::json& request = nlohmann::json::object()) {
  servoloop::ipc::IpcClient client = connectToWorld();
  const nlohmann::json reply = client.call(op, request, kWorldCallTimeoutS);
  if (reply.contains("stepped")) std::cout << "stepped " << reply.value("stepped", std::uint64_t{0}) << " steps; ";
  printState(reply);
}

void addWorldCommands(CLI::App& root) {
  CLI::App& world = commandGroup(root, "world", "Pause, step or reset the running world (Gazebo's physics controls)");
  world.add_subcommand("state", "Whether the world runs, its time and physics steps")->callback([] {
    callWorld("world.state");
  });
  world.add_subcommand("pause", "Pause the physics and the controllers (gazebo pause_physics)")->callback([] {
    callWorld("world.pause");
  });
  world.add_subcommand("unpause", "Let the world run again (gazebo unpause_physics)")->callback([] {
    callWorld("world.unpause");
  });
  auto steps = std::make_shared<std::uint64_t>(1);
  CLI::App* step = world.add_subcommand("step", "Run N physics steps of a paused world (default 1)");
  step->add_option("N", *steps, "Physics steps")->check(CLI::Range(std::uint64_t{1}, kMaxSteps));
  step->callback([steps] { callWorld("world.step", {{"steps", *steps}}); });
  world.add_subcommand("reset",
                       "Every robot and object back to its start, controllers restarted, time 0 "
                       "(gazebo reset_simulation)")
      ->callback([] { callWorld("world.reset"); });
}

}  // namespace
}  // namespace servoloop::cli

SERVOLOOP_CLI_COMMANDS(16, servoloop::cli::addWorldCommands)
