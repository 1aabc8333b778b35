// `servoloop model list | get NAME | set NAME --pose ... --twist ... |
// set-configuration NAME --joint J=POS... | delete NAME`: Gazebo's model
// services (get_model_state, set_model_state, set_model_configuration,
// delete_model) for the world served on default.sock (or the only node).
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
  std::vector<double> pose;         // x y z [roll pitch yaw | qx qy qz qw]
  std::vector<double> twist;        // vx vy vz [wx wy wz]
};

nlohmann::json vector3(double x, double y, double z) { return {{"x", x}, {"y", y}, {"z", z}}; }

// The request of `model set`: what was given over the model's current state.
nlohmann::json setStateRequest(const ModelOptions& options, const nlohmann::json& current) {
  for (const double value : options.pose) {
    if (!std::isfinite(value)) throw Error("--pose: every value must be a finite number");
  }
  for (const double value : options.twist) {
    if (!std::isfinite(value)) throw Error("--twist: every value must be a finite number");
  }
  nlohmann::json request = {{"model", options.model}};
  const std::vector<double>& p = options.pose;
  if (!p.empty()) {
    nlohmann::json pose = current.at("pose");
    pose["position"] = vector3(p[0], p[1], p[2]);
    if (p.size() == 6) {
      // URDF's rpy: R = Rz(yaw) Ry(pitch) Rx(roll).
      const double cr = std::cos(p[3] / 2), sr = std::sin(p[3] / 2);
      const double cp = std::cos(p[4] / 2), sp = std::sin(p[4] / 2);
      const double cy = std::cos(p[5] / 2), sy = std::sin(p[5] / 2);
      pose["orientation"] = {{"x", sr * cp * cy - cr * sp * sy},
                             {"y", cr * sp * cy + sr * cp * sy},
                             {"z", cr * cp * sy - sr * sp * cy},
                             {"w", cr * cp * cy + sr * sp * sy}};
    } else if (p.size() == 7) {
      pose["orientation"] = {{"x", p[3]}, {"y", p[4]}, {"z", p[5]}, {"w", p[6]}};
    }
    request["pose"] = pose;
  }
  const std::vector<double>& t = options.twist;
  if (!t.empty()) {
    nlohmann::json twist = current.at("twist");
    twist["linear"] = vector3(t[0], t[1], t[2]);
    if (t.size() == 6) twist["angular"] = vector3(t[3], t[4], t[5]);
    request["twist"] = twist;
  }
  return request;
}

void addModelCommands(CLI::App& root) {
  auto options = std::make_shared<ModelOptions>();
  CLI::App& model = commandGroup(root, "model", "The world's models: list, state, pose and twist, joint positions, delete (Gazebo's model services)");

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

  CLI::App* set_state = model.add_subcommand(
      "set", "Teleport a model's floating base and/or set its velocity (gazebo set_model_state)");
  set_state->add_option("NAME", options->model, "Model name or namespace")->required();
  set_state
      ->add_option("--pose", options->pose,
                   "Position x y z (m; the orientation stays), or x y z roll pitch yaw (rad, URDF's rpy), or x y z "
                   "qx qy qz qw, in the world frame")
      ->expected(3, 7)
      ->type_name("X Y Z [R P Y | QX QY QZ QW]");
  set_state
      ->add_option("--twist", options->twist,
                   "Linear velocity vx vy vz (m/s; the angular velocity stays), or vx vy vz wx wy wz (rad/s), in world "
                   "axes")
      ->expected(3, 6)
      ->type_name("VX VY VZ [WX WY WZ]");
  set_state->add_flag("--json", options->json, "Print the model's new state as JSON");
  set_state->callback([options] {
    if (options->pose.empty() && options->twist.empty()) throw Error("model set: give --pose and/or --twist");
    if (const std::size_t n = options->pose.size(); n != 0 && n != 3 && n != 6 && n != 7) {
      throw Error(fmt::format("--pose takes 3, 6 or 7 numbers (x y z [roll pitch yaw | qx qy qz qw]), got {}", n));
    }
    if (const std::size_t n = options->twist.size(); n != 0 && n != 3 && n != 6) {
      throw Error(fmt::format("--twist takes 3 or 6 numbers (vx vy vz [wx wy wz]), got {}", n));
    }
    auto client = connectToWorld();
    const nlohmann::json current = client.call("model.get", {{"model", options->model}}, kModelCallTimeoutS);
    const nlohmann::json reply =
        client.call("model.set_state", setStateRequest(*options, current), kModelCallTimeoutS);
    if (options->json) {
      std::cout << reply.dump(2) << "\n";
    } else {
      printModel(reply);
    }
  });

  CLI::App* remove = model.add_subcommand(
      "delete", "Take a model out of the world, its controllers stopped first (gazebo delete_model)");
  remove->add_option("NAME", options->model, "Model name or namespace")->required();
  remove->callback([options] {
    const nlohmann::json reply = connectToWorld().call("model.delete", {{"model", options->model}}, kModelCallTimeoutS);
    std::cout << "deleted " << reply.value("namespace", options->model) << "\n";
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
