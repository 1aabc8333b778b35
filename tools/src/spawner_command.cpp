// `servoloop spawner`: ros_control's controller spawner. Loads each named
// controller into a running node's controller manager (a failed one is
// reported and skipped), then starts every loaded one in one STRICT switch.
// YAML file arguments are loaded into the parameters first. Unlike ros_control,
// a controller manager that never appears is an error (non-zero exit).
#include <algorithm>
#include <csignal>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "node_connection.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::cli {
namespace {

namespace fs = std::filesystem;

struct SpawnerOptions {
  std::string ns;
  bool stopped = false;
  bool unload_on_kill = false;
  double timeout_s = 30.0;
  double shutdown_timeout_s = 10.0;
  std::vector<std::string> arguments;  // controller names and YAML files, in order
};

// How long one switch may take on the node: the real-time thread carries it
// out at the next cycle, which at a low real-time factor can be a while.
constexpr double kSpawnerSwitchTimeoutS = 30.0;

bool isYamlFile(const std::string& argument) {
  const auto extension = fs::path(argument).extension();
  std::error_code error;
  return (extension == ".yaml" || extension == ".yml") && fs::is_regular_file(argument, error);
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string joined;
  for (const auto& name : names) joined += (joined.empty() ? "" : ", ") + name;
  return joined;
}

nlohmann::json strictSwitch(const std::vector<std::string>& start,
                            const std::vector<std::string>& stop) {
  return {{"start", start},
          {"stop", stop},
          {"strictness", "strict"},
          {"start_asap", false},
          {"timeout", 0.0}};
}

// Stops the spawned controllers (STRICT) and unloads them in reverse order.
// Returns false if any step failed (each failure is reported on stderr).
bool stopAndUnload(servoloop::ipc::IpcClient& client, const std::vector<std::string>& loaded, bool started,
                   double timeout_s) {
  bool ok = true;
  const double call_timeout_s = timeout_s > 0.0 ? timeout_s : 0.0;
  if (started && !loaded.empty()) {
    std::cout << "Stopping controllers: " << joinNames(loaded) << std::endl;
    try {
      client.call("control.switch", strictSwitch({}, loaded), call_timeout_s);
    } catch (const std::exception& error) {
      std::cerr << "spawner: failed to stop controllers: " << error.what() << std::endl;
      ok = false;
    }
  }
  for (auto name = loaded.rbegin(); name != loaded.rend(); ++name) {
    try {
      client.call("control.unload", {{"name", *name}}, call_timeout_s);
      std::cout << "Unloaded controller '" << *name << "'" << std::endl;
    } catch (const std::exception& error) {
      std::cerr << "spawner: failed to unload '" << *name << "': " << error.what() << std::endl;
      ok = false;
    }
  }
  return ok;
}

void runSpawner(const SpawnerOptions& options) {
  if (options.timeout_s < 0.0) throw Error("--timeout must be >= 0 (0 waits forever)");
  // Signals are caught from the start, so a SIGTERM during spawning still
  // leads to a clean unload of what was spawned so far.
  if (options.unload_on_kill) installStopSignalHandlers();

  // As ROS's spawner says "Waiting for service ...": a user who started the
  // spawner before the node sees what it is waiting for.
  const std::string ns = normalizeNamespace(options.ns);
  const auto running = runningNodeNames();
  const bool present = ns.empty() ? !running.empty()
                                  : std::find(running.begin(), running.end(), ns) != running.end();
  if (!present) {
    std::cout << "spawner: waiting for the servoloop node"
              << (ns.empty() ? std::string() : " of namespace '" + ns + "'");
    if (options.timeout_s > 0.0) std::cout << " (up to " << options.timeout_s << " s)";
    std::cout << std::endl;
  }
  servoloop::ipc::IpcClient client = connectToRobotNode(options.ns, options.timeout_s, /*wait=*/true);

  // YAML files first, whatever their position among the names.
  std::vector<std::string> names;
  for (const auto& argument : options.arguments) {
    if (!isYamlFile(argument)) {
      names.push_back(argument);
      continue;
    }
    const std::string file = fs::absolute(argument).lexically_normal().string();
    client.call("param.load", {{"file", file}, {"namespace", "/"}});
    std::cout << "Loaded parameters from " << file << std::endl;
  }

  std::vector<std::string> loaded;
  bool all_loaded = true;
  for (const auto& name : names) {
    if (options.unload_on_kill && stopRequested()) break;
    try {
      client.call("control.load", {{"name", name}});
      loaded.push_back(name);
      std::cout << "Loaded controller '" << name << "'" << std::endl;
    } catch (const std::exception& error) {
      std::cerr << "spawner: failed to load '" << name << "': " << error.what() << std::endl;
      all_loaded = false;
    }
  }

  bool started = false;
  bool switch_ok = true;
  if (!options.stopped && !loaded.empty() && !(options.unload_on_kill && stopRequested())) {
    try {
      client.call("control.switch", strictSwitch(loaded, {}), kSpawnerSwitchTimeoutS);
      started = true;
      std::cout << "Started controllers: " << joinNames(loaded) << std::endl;
    } catch (const std::exception& error) {
      std::cerr << "spawner: failed to start controllers " << joinNames(loaded) << ": "
                << error.what() << std::endl;
      switch_ok = false;
    }
  }

  if (!options.unload_on_kill) {
    // Each failure has been reported on its own line already.
    if (!all_loaded || !switch_ok) throw CliExit{1};
    return;
  }

  // Stay until SIGINT/SIGTERM, then take back what this spawner added.
  if (!stopRequested()) {
    std::cout << "Spawner running; SIGINT or SIGTERM stops and unloads "
              << (loaded.empty() ? "nothing" : joinNames(loaded)) << std::endl;
  }
  while (!stopRequested()) sleepUnlessStopped(3600.0);
  if (!stopAndUnload(client, loaded, started, options.shutdown_timeout_s)) throw CliExit{1};
}

void addSpawnerCommand(CLI::App& root) {
  auto options = std::make_shared<SpawnerOptions>();
  CLI::App* spawner = root.add_subcommand(
      "spawner",
      "Load controllers into a running node and start them in one STRICT switch "
      "(ros_control's spawner)");
  addNamespaceOption(*spawner, options->ns);
  spawner->add_flag("--stopped", options->stopped, "Load the controllers but do not start them");
  spawner->add_flag("--unload-on-kill", options->unload_on_kill,
                    "Keep running; on SIGINT/SIGTERM stop the controllers and unload them in "
                    "reverse order");
  spawner
      ->add_option("--timeout", options->timeout_s,
                   "Seconds to wait for the node to appear (0 = forever)")
      ->capture_default_str()
      ->type_name("SECONDS")
      ->check(numberWithin(0.0, kMaxDurationS, "seconds; 0 waits forever"));
  spawner
      ->add_option("--shutdown-timeout", options->shutdown_timeout_s,
                   "Seconds each stop/unload request may take on shutdown (0 = forever)")
      ->capture_default_str()
      ->type_name("SECONDS")
      ->check(numberWithin(0.0, kMaxDurationS, "seconds; 0 waits forever"));
  spawner
      ->add_option("controllers", options->arguments,
                   "Controller names; an existing .yaml file is loaded into the parameters "
                   "(namespace /) before any controller")
      ->required()
      ->type_name("NAME|FILE.yaml");
  spawner->callback([options] { runSpawner(*options); });
}

}  // namespace
}  // namespace servoloop::cli

SERVOLOOP_CLI_COMMANDS(20, servoloop::cli::addSpawnerCommand)
