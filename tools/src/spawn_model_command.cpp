// `servoloop spawn-model`: gazebo_ros's spawn_model for a running world. Adds a
// robot from a URDF file to the world served on default.sock (or the only node).
#include <array>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "node_connection.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/description/xacro.hpp"

namespace servoloop::cli {
namespace {


// Spawning loads the model, its hardware and plugins on the node.
constexpr double kSpawnCallTimeoutS = 60.0;

struct SpawnModelOptions {
  std::string urdf;
  std::string model;
  std::string ns;
  std::vector<std::string> params;
  std::array<double, 6> pose{};  // x y z roll pitch yaw, as gazebo_ros spawn_model's -x -y -z -R -P -Y
  bool pose_given = false;
  bool fixed_base = false;
  std::vector<std::string> xacro_args;  // name:=value
};

void runSpawnModel(const SpawnModelOptions& options) {
  const std::string urdf = existingFileArgument(options.urdf, "--urdf file");
  nlohmann::json params = nlohmann::json::array();
  for (const auto& file : options.params) params.push_back(existingFileArgument(file, "--param file"));

  nlohmann::json request{{"urdf", urdf}, {"model", options.model}};
  if (!options.ns.empty()) request["namespace"] = normalizeNamespace(options.ns);
  if (!params.empty()) request["params"] = params;
  if (options.pose_given) request["pose"] = options.pose;
  if (options.fixed_base) request["fixed_base"] = true;
  for (const auto& arg : options.xacro_args) {
    const auto [name, value] = parseXacroArg(arg);
    request["xacro_args"][name] = value;
  }

  servoloop::ipc::IpcClient client = connectToWorld();
  const auto reply = client.call("model.spawn", request, kSpawnCallTimeoutS);
  for (const auto& warning : reply.value("warnings", nlohmann::json::array())) {
    if (warning.is_string()) std::cerr << "warning: " << warning.get<std::string>() << "\n";
  }
  std::cout << "Spawned model '" << options.model << "' in namespace "
            << reply.value("namespace", normalizeNamespace(options.ns)) << "\n";
}

void addSpawnModelCommand(CLI::App& root) {
  auto options = std::make_shared<SpawnModelOptions>();
  CLI::App* spawn = root.add_subcommand(
      "spawn-model", "Add a robot from a URDF file to the running world (gazebo_ros spawn_model)");
  spawn->add_option("--urdf", options->urdf, "URDF or xacro file")->required()->type_name("FILE");
  spawn->add_option("--xacro-arg", options->xacro_args, "xacro argument for a .xacro file (repeatable)")
      ->type_name("NAME:=VALUE");
  spawn->add_option("--model", options->model, "Model name")
      ->required()
      ->type_name("NAME")
      ->check([](const std::string& name) {
        return name.empty() ? std::string("a model needs a name (its default namespace is /NAME)") : std::string();
      });
  spawn->add_option("-N,--namespace", options->ns,
                    "Robot namespace (default: the URDF's robotNamespace, else /<model>)")
      ->type_name("NS");
  spawn->add_option("--param", options->params,
                    "YAML parameter file to load before the robot starts (repeatable)")
      ->type_name("FILE.yaml");
  const char* names[6] = {"-x", "-y", "-z", "-R", "-P", "-Y"};
  const char* help[6] = {"Spawn x (m)", "Spawn y (m)", "Spawn z (m)", "Spawn roll (rad)", "Spawn pitch (rad)",
                         "Spawn yaw (rad)"};
  for (int i = 0; i < 6; ++i) {
    spawn->add_option(names[i], options->pose[i], help[i])
        ->type_name("NUM")
        ->check(numberWithin(i < 3 ? -1e6 : -1e3, i < 3 ? 1e6 : 1e3, i < 3 ? "m" : "rad"));
  }
  spawn->add_flag("--fixed-base", options->fixed_base,
                  "Weld the robot's root link to the world at the spawn pose (pybullet's useFixedBase)");
  spawn->callback([options, spawn] {
    for (const char* name : {"-x", "-y", "-z", "-R", "-P", "-Y"}) options->pose_given |= spawn->count(name) > 0;
    for (const double value : options->pose) {
      if (!std::isfinite(value)) throw ConfigError("spawn-model: the spawn pose must be finite numbers (m, rad)");
    }
    runSpawnModel(*options);
  });
}

}  // namespace
}  // namespace servoloop::cli

SERVOLOOP_CLI_COMMANDS(15, servoloop::cli::addSpawnModelCommand)
