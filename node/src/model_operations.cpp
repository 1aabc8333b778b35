// The model operations of a node's IPC sockets (docs/node_operations.md),
// as Gazebo's model services: model.list, model.get (get_model_state),
// model.set_state (set_model_state), model.set_configuration
// (set_model_configuration), model.spawn (spawn_urdf_model) and
// model.delete (delete_model).
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/ipc/ipc_protocol.hpp"
#include "servoloop/node/node.hpp"
#include "servoloop/node/node_operations.hpp"
#include "request_fields.hpp"
#include "servoloop/node/robot_namespace.hpp"
#include "servoloop/params/parameter_store.hpp"
#include "servoloop/realtime/topic_bus.hpp"

namespace servoloop::node {

using nlohmann::json;

namespace {

// Reads `names` (e.g. x, y, z) of the object at request[group][part] into
// `out`: every one present and a finite number, else servoloop::Error naming
// the field.
template <std::size_t N>
void readComponents(const json& request, const char* group, const char* part, const std::array<const char*, N>& names,
                    double (&out)[N]) {
  const std::string where = std::string(group) + "." + part;
  const json& object = request.at(group);
  const auto it = object.find(part);
  if (it == object.end() || !it->is_object()) {
    ipc::throwBadRequestField(request, where,
                              N == 4 ? "an object {x, y, z, w} of finite numbers" : "an object {x, y, z} of finite numbers",
                              it == object.end() ? json() : *it);
  }
  for (std::size_t i = 0; i < N; ++i) {
    const json::const_iterator value = it->find(names[i]);
    if (value == it->end() || !value->is_number() || !std::isfinite(value->get<double>())) {
      ipc::throwBadRequestField(request, where + "." + names[i], "a finite number",
                                value == it->end() ? json() : *value);
    }
    out[i] = value->get<double>();
  }
}

bool hasGroup(const json& request, const char* group) {
  const auto it = request.find(group);
  if (it == request.end() || it->is_null()) return false;
  if (!it->is_object()) ipc::throwBadRequestField(request, group, "an object", *it);
  return true;
}

}  // namespace

json modelStateToJson(const ModelState& state) {
  const auto vector3 = [](const double (&v)[3]) { return json{{"x", v[0]}, {"y", v[1]}, {"z", v[2]}}; };
  return {{"name", state.name},
          {"namespace", state.ns},
          {"fixed", state.fixed},
          {"pose",
           {{"position", vector3(state.position)},
            {"orientation",
             {{"x", state.orientation[0]}, {"y", state.orientation[1]}, {"z", state.orientation[2]},
              {"w", state.orientation[3]}}}}},
          {"twist", {{"linear", vector3(state.linear_velocity)}, {"angular", vector3(state.angular_velocity)}}}};
}

json setModelStateFromJson(Node& node, const json& request) {
  const std::string model = ipc::requireRequestString(request, "model");
  std::optional<ModelPose> pose;
  std::optional<ModelTwist> twist;
  constexpr std::array<const char*, 3> xyz{"x", "y", "z"};
  if (hasGroup(request, "pose")) {
    pose.emplace();
    readComponents(request, "pose", "position", xyz, pose->position);
    readComponents(request, "pose", "orientation", std::array<const char*, 4>{"x", "y", "z", "w"}, pose->orientation);
  }
  if (hasGroup(request, "twist")) {
    twist.emplace();
    readComponents(request, "twist", "linear", xyz, twist->linear);
    readComponents(request, "twist", "angular", xyz, twist->angular);
  }
  if (!pose && !twist) {
    throw Error("model.set_state: give 'pose' {position, orientation} and/or 'twist' {linear, angular}");
  }
  node.setModelState(model, pose, twist);
  return modelStateToJson(node.modelState(model));
}

json NodeOperations::modelOp(const std::string& op, const json& request, ipc::IpcConnection& connection) {
  if (op == "model.list") {
    json models = json::array();
    for (const std::string& ns : node_.robotNamespaces()) {
      try {
        models.push_back(modelStateToJson(node_.modelState(ns)));
      } catch (const Error&) {
        // deleted meanwhile
      }
    }
    return {{"models", std::move(models)}};
  }
  if (op == "model.get") return modelStateToJson(node_.modelState(ipc::requireRequestString(request, "model")));
  if (op == "model.set_state") return setModelStateFromJson(node_, request);
  if (op == "model.set_configuration") {
    const std::string model = ipc::requireRequestString(request, "model");
    std::vector<double> positions;
    const auto given = request.find("joint_positions");
    if (given == request.end() || !given->is_array()) {
      if (given == request.end() || given->is_null()) {
        throw Error("model.set_configuration: 'joint_positions' is required (a list of numbers, one per joint name)");
      }
      ipc::throwBadRequestField(request, "joint_positions", "a list of numbers, one per joint name", *given);
    }
    for (std::size_t i = 0; i < given->size(); ++i) {
      const json& position = (*given)[i];
      if (!position.is_number() || !std::isfinite(position.get<double>())) {
        ipc::throwBadRequestField(request, "joint_positions[" + std::to_string(i) + "]", "a finite number",
                                  position);
      }
      positions.push_back(position.get<double>());
    }
    node_.setModelConfiguration(model, stringList(request, "joint_names"), positions);
    return nullptr;
  }
  if (op == "model.spawn") {
    return deferToWorker(request, connection, [this, request] { return modelSpawn(request); });
  }
  if (op == "model.delete") {
    const std::string model = ipc::requireRequestString(request, "model");
    return deferToWorker(request, connection, [this, model] { return json{{"namespace", node_.deleteModel(model)}}; });
  }
  throw Error("unknown op '" + op + "'; the model operations are model.{list,get,set_state,set_configuration,spawn,delete}");
}

json NodeOperations::modelSpawn(const json& request) {
  RobotSpec spec;
  spec.urdf = ipc::requireRequestString(request, "urdf");
  if (!spec.urdf.is_absolute()) throw Error("'model.spawn': urdf '" + spec.urdf.string() + "' must be an absolute path");
  if (!std::filesystem::is_regular_file(spec.urdf)) {
    throw Error("'model.spawn': URDF file '" + spec.urdf.string() + "' does not exist");
  }
  spec.model = ipc::requestString(request, "model", "");
  spec.robot_namespace = ipc::requestString(request, "namespace", "");
  // The names are checked before anything is built: a robot refused after
  // it runs would be one nobody can reach.
  if (request.contains("model")) {
    const bool plain = !spec.model.empty() && std::isalpha(static_cast<unsigned char>(spec.model.front())) &&
                       std::all_of(spec.model.begin(), spec.model.end(), [](char c) {
                         return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                       });
    if (!plain) {
      throw ConfigError("'model.spawn': model name '" + spec.model +
                        "' is not a ROS base name: it must start with a letter and hold only letters, digits and "
                        "'_' (it is the robot's default namespace /<model>)");
    }
  }
  {
    const std::string chosen = spec.robot_namespace.empty() && !spec.model.empty() ? "/" + spec.model
                                                                                   : spec.robot_namespace;
    if (!chosen.empty()) {
      std::string resolved;
      try {
        resolved = params::resolveName("/", chosen);
        if (resolved != "/") realtime::TopicBus::normalizeTopicName(resolved);
      } catch (const Error& e) {
        throw ConfigError("'model.spawn': robot namespace '" + chosen + "' is not a ROS graph name (" + e.what() +
                          "); give e.g. -N /my_robot");
      }
      if (const std::string problem = spawnNamespaceProblem(resolved); !problem.empty()) {
        throw ConfigError("'model.spawn': robot namespace '" +
                          (chosen.size() > 80 ? chosen.substr(0, 80) + "..." : chosen) + "' " + problem);
      }
    }
  }
  for (const std::string& file : stringList(request, "params")) {
    if (!std::filesystem::path(file).is_absolute()) {
      throw Error("'model.spawn': params file '" + file + "' must be an absolute path");
    }
    spec.params.push_back(ParameterFile{file, "/", "", ""});
  }
  if (request.contains("pose")) {
    const nlohmann::json& pose = request["pose"];
    if (!pose.is_array() || (pose.size() != 3 && pose.size() != 6)) {
      throw Error("'model.spawn': pose must be [x, y, z] or [x, y, z, roll, pitch, yaw]");
    }
    std::array<double, 6> values{};
    for (std::size_t i = 0; i < pose.size(); ++i) {
      if (!pose[i].is_number() || !std::isfinite(pose[i].get<double>())) {
        throw Error("'model.spawn': pose[" + std::to_string(i) + "] must be a finite number");
      }
      values[i] = pose[i].get<double>();
    }
    spec.pose = values;
  }
  if (request.contains("xacro_args")) {
    const nlohmann::json& args = request["xacro_args"];
    if (!args.is_object()) throw Error("'model.spawn': xacro_args must be an object of name: value strings");
    for (const auto& [name, value] : args.items()) {
      if (!value.is_string()) throw Error("'model.spawn': xacro_args." + name + " must be a string");
      spec.xacro_args[name] = value.get<std::string>();
    }
  }
  if (request.contains("fixed_base")) {
    if (!request["fixed_base"].is_boolean()) throw Error("'model.spawn': fixed_base must be true or false");
    spec.fixed_base = request["fixed_base"].get<bool>();
  }
  // What the spawn warned about (a robot starting in the floor, a URDF that
  // needed mending) goes back to the client too, not only to the node's log.
  const ThreadLogCapture capture;
  const std::string robot_namespace = node_.spawnRobot(spec);
  return {{"namespace", robot_namespace}, {"warnings", capture.warnings()}};
}

}  // namespace servoloop::node
