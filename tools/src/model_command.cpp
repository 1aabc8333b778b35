// `servoloop model list | get NAME | set-configuration NAME --joint J=POS...`:
// Gazebo's model services (get_model_state, set_model_configuration) for the
// world served on default.sock (or the only node).
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "node_connection.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::cli {
namespace {

constexpr double kModelCallTimeoutS = 30.0;

// The whole text as a finite number.
bool parseFiniteDouble(const std::string& text, double& out) {
  if (text.empty()) return false;
  char* end = nullptr;
  out = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(out);
}

double field(const nlohmann::json& object, const char* a, const char* b) {
  return object.at(a).at(b).get<double>();
}

void printModel(const nlohmann::json& model) {
  const nlohmann::json& pose = model.at("pose");
  const nlohmann::json& twist = model.at("twist");
  std::cout << model.value("name", "") << " (" << model.value("namespace", "") << ")"
            << (model.value("fixed", false) ? ", fixed base" : "") << "\n"
            << fmt::format("  position:    [{}, {}, {}]\n", field(pose, "position", "x"), field(pose, "position", "y"),
                           field(pose, "position", "z"))
            << fmt::format("  orientation: [{}, {}, {}, {}] (x y z w)\n", field(pose, "orientation", "x"),
                           field(pose, "orientation", "y"), field(pose, "orientation", "z"),
                           field(pose, "orientation", "w"))
            << fmt::format("  linear:      [{}, {}, {}]\n", field(twist, "linear", "x"), field(twist, "linear", "y"),
                           field(twist, "linear", "z"))
            << fmt::format("  angular:     [{}, {}, {}]\n", field(twist, "angular", "x"),
                           field(twist, "angular", "y"), field(twist, "angular", "z"));
}

struct ModelOptions {
  std::string model;
  bool json = false;
  std::vector<std::string> joints;  // NAME=POSITION
};

void addModelCommands(CLI::App& root) {
  auto options = std::make_shared<ModelOptions>();
  CLI::App& model = commandGroup(root, "model", "The world's models: list, state, joint positions (Gazebo's model services)");

  CLI::App* list = model.add_subcommand("list", "Every model with its pose and twist");
  list->add_flag("--json", options->json, "Print the reply as JSON");
  list->callback([options] {
    const nlohmann::json reply = connectToWorld().call("model.list", nlohmann::json::object(), kModelCallTimeoutS);
    if (options->json) {
      std::cout << reply.at("models").dump(2) << "\n";
      return;
    }
    for (const nlohmann::json& entry : reply.at("models")) printModel(entry);
  });

  CLI::App* get = model.add_subcommand("get", "A model's pose and twist in the world frame (gazebo get_model_state)");
  get->add_option("NAME", options->model, "Model name or namespace")->required();
  get->add_flag("--json", options->json, "Print the reply as JSON");
  get->callback([options] {
    const nlohmann::json reply = connectToWorld().call("model.get", {{"model", options->model}}, kModelCallTimeoutS);
    if (options->json) {
      std::cout << reply.dump(2) << "\n";
    } else {
      printModel(reply);
    }
  });

  CLI::App* set = model.add_subcommand(
      "set-configuration", "Move joints of a model to positions, at rest (gazebo set_model_configuration)");
  set->add_option("NAME", options->model, "Model name or namespace")->required();
  set->add_option("--joint", options->joints, "A joint and its position (rad or m); repeatable")
      ->required()
      ->type_name("NAME=POSITION");
  set->callback([options] {
    nlohmann::json names = nlohmann::json::array();
    nlohmann::json positions = nlohmann::json::array();
    for (const std::string& entry : options->joints) {
      const auto equals = entry.find('=');
      double position = 0.0;
      if (equals == std::string::npos || equals == 0 || !parseFiniteDouble(entry.substr(equals + 1), position)) {
        throw Error(fmt::format("--joint '{}' must be NAME=POSITION with a finite number, e.g. joint1=0.5", entry));
      }
      names.push_back(entry.substr(0, equals));
      positions.push_back(position);
    }
    connectToWorld().call("model.set_configuration",
                          {{"model", options->model}, {"joint_names", names}, {"joint_positions", positions}},
                          kModelCallTimeoutS);
    std::cout << "set " << names.size() << " joint(s) of " << options->model << "\n";
  });
}

}  // namespace
}  // namespace servoloop::cli

SERVOLOOP_CLI_COMMANDS(17, servoloop::cli::addModelCommands)
