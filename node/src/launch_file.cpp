// Launch file parsing: every problem becomes one ConfigError naming the file,
// line, key and fix.
#include "servoloop/node/launch_file.hpp"
#include "servoloop/node/roslaunch_xml.hpp"
#include "servoloop/node/sdf_world_launch.hpp"

#include <sched.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include "launch_file_keys.hpp"
#include "servoloop/core/text_file.hpp"
#include "servoloop/core/time.hpp"
#include "servoloop/description/sdf_world.hpp"
#include "servoloop/node/message_json.hpp"
#include "servoloop/params/parameter_store.hpp"
#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::node {
namespace {

namespace fs = std::filesystem;

constexpr const char* kFloat64 = "std_msgs/Float64";
constexpr const char* kFloat64MultiArray = "std_msgs/Float64MultiArray";

// Where a node sits in the file, for error messages.
class Parser {
 public:
  Parser(std::string_view source_name, fs::path base_directory)
      : source_(source_name), base_(std::move(base_directory)) {}

  // world.file, once world() has read it ("" when not given).
  const fs::path& worldFile() const { return world_file_; }

  // "file:line:column: key" of a node, for errors.
  std::string at(const YAML::Node& node, const std::string& key) const {
    std::string where = source_;
    if (node.IsDefined() && node.Mark().line >= 0) {
      where += fmt::format(":{}:{}", node.Mark().line + 1, node.Mark().column + 1);
    }
    return key.empty() ? where : where + ": " + key;
  }

  [[noreturn]] void fail(const YAML::Node& node, const std::string& key, const std::string& problem) const {
    throw ConfigError(at(node, key) + ": " + problem);
  }

  void requireMap(const YAML::Node& node, const std::string& key, const char* example) const {
    if (!node.IsMap()) fail(node, key, fmt::format("expected a map, e.g. {}, got {}", example, describe(node)));
  }

  // Every key of map must be one the schema declares (launch_file_keys.cpp).
  void checkKeys(const YAML::Node& map, const std::string& key, const params::Schema& schema) const {
    for (const auto& entry : map) {
      const std::string name = entry.first.Scalar();
      if (schema.find(name) != nullptr) continue;
      const std::string_view suggestion = schema.closest(name);
      fail(entry.first, key.empty() ? name : key + "." + name,
           fmt::format("unknown key '{}'{}; the keys here are: {} (check the spelling)", name,
                       suggestion.empty() ? "" : fmt::format(" (did you mean '{}'?)", suggestion),
                       schema.keyNames()));
    }
  }

  static std::string describe(const YAML::Node& node) {
    if (!node.IsDefined() || node.IsNull()) return "nothing";
    if (node.IsScalar()) return "'" + node.Scalar() + "'";
    if (node.IsSequence()) return "a list";
    return "a map";
  }

  double number(const YAML::Node& node, const std::string& key) const {
    const params::ParamType type = node.IsDefined() ? params::paramTypeOf(node) : params::ParamType::null;
    if (type != params::ParamType::integer && type != params::ParamType::floating) {
      fail(node, key, "expected a number, got " + describe(node));
    }
    const double value = params::paramDoubleValue(node);
    if (!std::isfinite(value)) fail(node, key, "expected a finite number, got " + describe(node));
    return value;
  }

  double positiveNumber(const YAML::Node& node, const std::string& key, const char* unit) const {
    const double value = number(node, key);
    if (!(value > 0.0)) fail(node, key, fmt::format("expected a value > 0 {}, got {}", unit, describe(node)));
    return value;
  }

  double nonNegativeNumber(const YAML::Node& node, const std::string& key, const char* unit) const {
    const double value = number(node, key);
    if (value < 0.0) fail(node, key, fmt::format("expected a value >= 0 {}, got {}", unit, describe(node)));
    return value;
  }

  bool boolean(const YAML::Node& node, const std::string& key) const {
    if (params::paramTypeOf(node) != params::ParamType::boolean) fail(node, key, "expected true or false, got " + describe(node));
    return node.as<bool>();
  }

  std::string string(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar() || node.Scalar().empty()) fail(node, key, "expected a non-empty string, got " + describe(node));
    return node.Scalar();
  }

  // A list of strings; a single string is taken as a list of one.
  std::vector<std::string> strings(const YAML::Node& node, const std::string& key) const {
    std::vector<std::string> values;
    if (!node.IsDefined() || node.IsNull()) return values;
    if (node.IsScalar()) return {string(node, key)};
    if (!node.IsSequence()) fail(node, key, "expected a list of names, e.g. [a, b], got " + describe(node));
    for (std::size_t i = 0; i < node.size(); ++i) values.push_back(string(node[i], fmt::format("{}[{}]", key, i)));
    return values;
  }

  fs::path path(const YAML::Node& node, const std::string& key) const {
    const fs::path given = string(node, key);
    return (given.is_absolute() ? given : base_ / given).lexically_normal();
  }

  fs::path existingFile(const YAML::Node& node, const std::string& key, const char* what) const {
    const fs::path file = path(node, key);
    if (!fs::is_regular_file(file)) {
      fail(node, key,
           fmt::format("{} '{}' does not exist (looked for {}); paths are relative to the launch file's folder",
                       what, node.Scalar(), file.string()));
    }
    return file;
  }

  std::string topic(const YAML::Node& node, const std::string& key) const {
    const std::string name = string(node, key);
    try {
      return realtime::TopicBus::normalizeTopicName(name);
    } catch (const Error& e) {
      fail(node, key, e.what());
    }
  }

  WorldSettings world(const YAML::Node& node) const {
    WorldSettings world;
    if (!node.IsDefined() || node.IsNull()) return world;
    requireMap(node, "world", "{backend: bullet, time_step: 0.001}");
    checkKeys(node, "world", launch_keys::world());
    if (node["clock"]) {
      const std::string clock = string(node["clock"], "world.clock");
      if (clock != "sim" && clock != "wall") {
        fail(node["clock"], "world.clock", "expected 'sim' (lockstep with the physics) or 'wall' (paced by the wall clock, as hardware), got '" + clock + "'");
      }
      world.wall_clock = clock == "wall";
    }
    if (node["backend"]) world.backend = string(node["backend"], "world.backend");
    if (node["time_step"]) {
      world.time_step_s = number(node["time_step"], "world.time_step");
      if (!(world.time_step_s >= kMinTimeStepS && world.time_step_s <= kMaxTimeStepS)) {
        fail(node["time_step"], "world.time_step",
             fmt::format("expected a time step from {} to {} s, got {}", kMinTimeStepS, kMaxTimeStepS,
                         describe(node["time_step"])));
      }
    }
    if (const YAML::Node gravity = node["gravity"]) {
      if (!gravity.IsSequence() || gravity.size() != 3) {
        fail(gravity, "world.gravity", "expected 3 numbers [x, y, z] in m/s², got " + describe(gravity));
      }
      for (std::size_t i = 0; i < 3; ++i) world.gravity[i] = number(gravity[i], fmt::format("world.gravity[{}]", i));
    }
    if (node["ground_plane"]) world.ground_plane = boolean(node["ground_plane"], "world.ground_plane");
    if (node["real_time_factor"]) {
      world.real_time_factor = nonNegativeNumber(node["real_time_factor"], "world.real_time_factor",
                                                 "(0 runs as fast as possible)");
    }
    if (node["file"]) world_file_ = existingFile(node["file"], "world.file", "world file");
    if (node["shared"]) world.shared = boolean(node["shared"], "world.shared");
    return world;
  }

  ControllerManagerSettings controllerManager(const YAML::Node& node) const {
    ControllerManagerSettings settings;
    if (!node.IsDefined() || node.IsNull()) return settings;
    requireMap(node, "controller_manager", "{update_rate: 1000}");
    checkKeys(node, "controller_manager", launch_keys::controllerManager());
    if (node["update_rate"]) {
      settings.update_rate_hz = positiveNumber(node["update_rate"], "controller_manager.update_rate", "Hz");
    }
    return settings;
  }

  RobotSpec robot(const YAML::Node& node, const std::string& key) const {
    requireMap(node, key, "{urdf: robot.urdf, controllers: [joint_state_controller]}");
    checkKeys(node, key, launch_keys::robot());
    RobotSpec robot;
    if (!node["urdf"]) fail(node, key, "missing 'urdf': give the robot description, e.g. urdf: robot.urdf");
    robot.urdf = existingFile(node["urdf"], key + ".urdf", "URDF file");
    if (const YAML::Node args = node["xacro_args"]; args.IsDefined() && !args.IsNull()) {
      if (!args.IsMap()) fail(args, key + ".xacro_args", "expected a map of xacro arguments, e.g. {prefix: left_}, got " + describe(args));
      for (const auto& kv : args) {
        const std::string name = kv.first.as<std::string>();
        robot.xacro_args[name] = string(kv.second, key + ".xacro_args." + name);
      }
    }
    if (node["model"]) robot.model = string(node["model"], key + ".model");
    if (node["namespace"]) {
      const std::string ns = string(node["namespace"], key + ".namespace");
      try {
        // Namespaces follow the rules of topic names (they prefix every
        // topic); "/" is the root namespace, as a robot launched without <group ns>.
        robot.robot_namespace = ns == "/" ? ns : realtime::TopicBus::normalizeTopicName(ns);
      } catch (const Error& e) {
        fail(node["namespace"], key + ".namespace", e.what());
      }
    }
    const YAML::Node params = node["params"];
    if (params.IsDefined() && !params.IsNull()) {
      if (params.IsScalar() || params.IsMap()) {
        robot.params.push_back(parameterFile(params, key + ".params"));
      } else if (!params.IsSequence()) {
        fail(params, key + ".params", "expected a list of YAML files, got " + describe(params));
      }
      for (std::size_t i = 0; params.IsSequence() && i < params.size(); ++i) {
        robot.params.push_back(parameterFile(params[i], fmt::format("{}.params[{}]", key, i)));
      }
    }
    robot.controllers = strings(node["controllers"], key + ".controllers");
    robot.stopped_controllers = strings(node["stopped_controllers"], key + ".stopped_controllers");
    if (node["fixed_base"]) robot.fixed_base = boolean(node["fixed_base"], key + ".fixed_base");
    if (node["self_collide"]) robot.self_collide = boolean(node["self_collide"], key + ".self_collide");
    if (const YAML::Node pose = node["pose"]) {
      if (!pose.IsSequence() || (pose.size() != 3 && pose.size() != 6)) {
        fail(pose, key + ".pose",
             "expected [x, y, z] or [x, y, z, roll, pitch, yaw] (m, rad), got " + describe(pose));
      }
      std::array<double, 6> values{};
      for (std::size_t i = 0; i < pose.size(); ++i) values[i] = number(pose[i], fmt::format("{}.pose[{}]", key, i));
      robot.pose = values;
    }
    if (node["realtime"] && !node["realtime"].IsNull()) robot.realtime = realtime(node["realtime"], key + ".realtime");
    if (const YAML::Node hardware = node["hardware"]; hardware.IsDefined() && !hardware.IsNull()) {
      const std::string where = key + ".hardware";
      requireMap(hardware, where, "{type: my_robot_hw/MyRobotHW, port: /dev/ttyUSB0}");
      if (!hardware["type"]) {
        fail(hardware, where, "missing 'type': the hardware plugin's type (kind robot_hw), e.g. {type: my_robot_hw/MyRobotHW}");
      }
      robot.hardware_type = string(hardware["type"], where + ".type");
      YAML::Node params(YAML::NodeType::Map);
      for (const auto& kv : hardware) {
        if (kv.first.as<std::string>() != "type") params[kv.first] = kv.second;
      }
      robot.hardware_params_yaml = YAML::Dump(params);
      robot.hardware_source = fmt::format("{}:{}", source_, hardware.Mark().line + 1);
    }
    return robot;
  }

  RealtimeSettings realtime(const YAML::Node& node, const std::string& key) const {
    requireMap(node, key, "{priority: 80, cpu_affinity: [1], lock_memory: true}");
    checkKeys(node, key, launch_keys::realtime());
    RealtimeSettings settings;
    const auto whole = [&](const YAML::Node& value, const std::string& where, double low, double high,
                           const std::string& what) {
      const double x = number(value, where);
      if (x != std::floor(x) || x < low || x > high) {
        fail(value, where, fmt::format("expected {}, a whole number from {} to {}, got {}", what, low, high, x));
      }
      return static_cast<int>(x);
    };
    if (node["priority"]) settings.priority = whole(node["priority"], key + ".priority", 1, 99, "a SCHED_FIFO priority");
    if (const YAML::Node cpus = node["cpu_affinity"]; cpus.IsDefined() && !cpus.IsNull()) {
      if (cpus.IsScalar()) {
        settings.cpu_affinity.push_back(whole(cpus, key + ".cpu_affinity", 0, CPU_SETSIZE - 1, "a CPU number"));
      } else if (cpus.IsSequence() && cpus.size() > 0) {
        for (std::size_t i = 0; i < cpus.size(); ++i) {
          settings.cpu_affinity.push_back(
              whole(cpus[i], fmt::format("{}.cpu_affinity[{}]", key, i), 0, CPU_SETSIZE - 1, "a CPU number"));
        }
      } else {
        fail(cpus, key + ".cpu_affinity", "expected a list of CPU numbers, e.g. [1], got " + describe(cpus));
      }
    }
    if (node["lock_memory"]) settings.lock_memory = boolean(node["lock_memory"], key + ".lock_memory");
    return settings;
  }

  // "file.yaml" (loaded at /) or {file: file.yaml, ns: /robot} (loaded under ns).
  ParameterFile parameterFile(const YAML::Node& node, const std::string& key) const {
    ParameterFile parameters;
    if (node.IsScalar()) {
      parameters.file = existingFile(node, key, "parameter file");
      return parameters;
    }
    requireMap(node, key, "{file: controllers.yaml, ns: /robot}");
    checkKeys(node, key, launch_keys::parameterFile());
    if (!node["file"]) fail(node, key, "missing 'file': the YAML file to load, e.g. {file: controllers.yaml, ns: /robot}");
    parameters.file = existingFile(node["file"], key + ".file", "parameter file");
    if (node["ns"]) {
      const std::string ns = string(node["ns"], key + ".ns");
      try {
        parameters.ns = params::resolveName("/", ns);
      } catch (const Error& e) {
        fail(node["ns"], key + ".ns", e.what());
      }
    }
    return parameters;
  }

  TimedPublication publication(const YAML::Node& node, const std::string& key) const {
    requireMap(node, key, "{topic: /robot/controller/command, value: 1.0, time: 0.5}");
    checkKeys(node, key, launch_keys::publication());
    if (!node["topic"]) fail(node, key, "missing 'topic'");
    if (!node["value"]) fail(node, key, "missing 'value': the message to publish, e.g. value: 1.0");
    const std::string topic_name = topic(node["topic"], key + ".topic");
    const std::string type = node["type"] ? string(node["type"], key + ".type") : "";
    const double time_s = node["time"] ? nonNegativeNumber(node["time"], key + ".time", "s of simulated time") : 0.0;
    TimedPublication publication;
    try {
      publication = makeTimedPublication(topic_name, type, yamlToJson(node["value"]), time_s, "");
    } catch (const Error& e) {
      fail(node["value"], key + ".value", e.what());
    }
    // Checked when the node types it: its errors then name where it was written.
    if (publication.type_inferred) publication.origin = at(node["value"], key + ".value");
    return publication;
  }

  RecordSpec record(const YAML::Node& node, const std::string& key) const {
    requireMap(node, key, "{topic: /robot/joint_states, file: joint_states.csv}");
    checkKeys(node, key, launch_keys::recording());
    if (!node["topic"]) fail(node, key, "missing 'topic'");
    if (!node["file"]) fail(node, key, "missing 'file': the CSV file to write, e.g. file: joint_states.csv");
    return RecordSpec{topic(node["topic"], key + ".topic"), path(node["file"], key + ".file")};
  }

  template <class Item>
  std::vector<Item> list(const YAML::Node& node, const std::string& key,
                         Item (Parser::*parse_item)(const YAML::Node&, const std::string&) const) const {
    std::vector<Item> items;
    if (!node.IsDefined() || node.IsNull()) return items;
    if (!node.IsSequence()) fail(node, key, "expected a list (entries start with '- '), got " + describe(node));
    for (std::size_t i = 0; i < node.size(); ++i) items.push_back((this->*parse_item)(node[i], fmt::format("{}[{}]", key, i)));
    return items;
  }

 private:
  std::string source_;
  fs::path base_;
  mutable fs::path world_file_;  // set by world()
};

std::string knownTypesList() {
  std::string list;
  for (const std::string& type : knownMessageTypes()) list += (list.empty() ? "" : ", ") + type;
  return list;
}

}  // namespace

TimedPublication makeTimedPublication(std::string topic, std::string type, const nlohmann::json& value,
                                      double time_s, std::string_view where) {
  if (type.empty() && value.is_object()) {
    // A message with fields: typed when the node knows what the topic
    // carries (withTopicType).
    TimedPublication untyped;
    untyped.topic = std::move(topic);
    untyped.type = kFloat64;
    untyped.message = value;
    untyped.time_s = time_s;
    untyped.type_inferred = true;
    untyped.origin = where;
    return untyped;
  }
  if (type.empty()) type = value.is_array() ? kFloat64MultiArray : kFloat64;
  const std::string prefix = where.empty() ? "" : std::string(where) + ": ";
  if (!isKnownMessageType(type)) {
    throw Error(fmt::format("{}unknown message type '{}' (known types: {})", prefix, type, knownTypesList()));
  }
  try {
    (void)normalizeMessage(type, value);
    requireFiniteCommand(type, value);
  } catch (const Error& e) {
    throw Error(prefix + e.what());
  }
  TimedPublication typed;
  typed.topic = std::move(topic);
  typed.type = std::move(type);
  typed.message = value;
  typed.time_s = time_s;
  typed.origin = where;
  return typed;
}

TimedPublication withTopicType(const TimedPublication& publication, std::string_view topic_type) {
  if (!publication.type_inferred) return publication;
  const std::string type = !topic_type.empty() ? std::string(topic_type) : std::string(kFloat64);
  return makeTimedPublication(publication.topic, type, publication.message, publication.time_s, publication.origin);
}

LaunchFile parseLaunchFile(std::string_view yaml, std::string_view source_name, const fs::path& base_directory) {
  const Parser parser(source_name, base_directory);
  YAML::Node root;
  try {
    root = YAML::Load(std::string(yaml));
  } catch (const YAML::DeepRecursion& e) {
    // yaml-cpp stops at a fixed depth with "bad file", which reads as a
    // syntax error; e.depth() is the level refused, one past the limit.
    throw ConfigError(fmt::format("{}: the YAML nests deeper than yaml-cpp's limit of {} levels{}; no launch file "
                                  "needs that: flatten it",
                                  source_name, e.depth() - 1,
                                  e.mark.is_null() ? std::string() : fmt::format(" (at line {})", e.mark.line + 1)));
  } catch (const YAML::ParserException& e) {
    throw ConfigError(fmt::format("{}:{}:{}: not valid YAML: {}", source_name, e.mark.line + 1, e.mark.column + 1, e.msg));
  }
  LaunchFile launch;
  if (root.IsNull() || !root.IsDefined()) return launch;
  params::checkYamlDocument(root, source_name);
  parser.requireMap(root, "", "world: {backend: bullet} and robots: [...]");
  parser.checkKeys(root, "", launch_keys::top());
  if (root["realtime"] && !root["realtime"].IsNull()) launch.realtime = parser.realtime(root["realtime"], "realtime");
  launch.world = parser.world(root["world"]);
  launch.controller_manager = parser.controllerManager(root["controller_manager"]);
  launch.robots = parser.list(root["robots"], "robots", &Parser::robot);
  if (const fs::path& world_file = parser.worldFile(); !world_file.empty()) {
    // The world file's models come first; what the launch file says of the
    // world itself wins over what the world file says.
    const YAML::Node world = root["world"];
    GivenWorldSettings given;
    given.time_step = static_cast<bool>(world["time_step"]);
    given.gravity = static_cast<bool>(world["gravity"]);
    given.ground_plane = static_cast<bool>(world["ground_plane"]);
    addSdfWorld(world_file, launch.world, launch.robots, given);
  }
  launch.publish = parser.list(root["publish"], "publish", &Parser::publication);
  launch.record = parser.list(root["record"], "record", &Parser::record);
  if (root["plot"] && !root["plot"].IsNull()) launch.plot = parser.path(root["plot"], "plot");
  if (root["ros1_bridge"] && !root["ros1_bridge"].IsNull()) launch.ros1_bridge = parser.boolean(root["ros1_bridge"], "ros1_bridge");
  return launch;
}

LaunchFile loadLaunchFile(const fs::path& path, const std::map<std::string, std::string>& roslaunch_args) {
  if (isRoslaunchPath(path)) return loadRoslaunchFile(path, roslaunch_args);
  if (isSdfWorldPath(path)) {
    if (!roslaunch_args.empty()) {
      throw ConfigError(fmt::format("{}: name:=value arguments are for ROS .launch files; a world file takes none",
                                    path.string()));
    }
    return loadSdfWorldLaunch(path);
  }
  if (!roslaunch_args.empty()) {
    throw ConfigError(fmt::format("{}: name:=value arguments ({}:={}) are for ROS .launch files; a YAML launch file "
                                  "takes none (a .xacro robot takes xacro_args: in the file)",
                                  path.string(), roslaunch_args.begin()->first, roslaunch_args.begin()->second));
  }
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    throw ConfigError(fmt::format("launch file '{}' cannot be read (no such file); check the path", path.string()));
  }
  const std::string text = readTextFile(path, "launch file");
  const fs::path absolute = fs::absolute(path).lexically_normal();
  LaunchFile launch = parseLaunchFile(text, path.string(), absolute.parent_path());
  launch.source = absolute;
  return launch;
}

TimedPublication parsePubFlag(std::string_view text) {
  const std::string flag = fmt::format("--pub '{}'", text);
  const std::string form =
      "expected TOPIC[:TYPE]:=VALUE[@TIME], e.g. /robot/controller/command:=1.0@0.5 or "
      "/arm/controller/command:trajectory_msgs/JointTrajectory:='{joint_names: [j1], points: [...]}'";
  const std::size_t assign = text.find(":=");
  if (assign == std::string_view::npos || assign == 0 || assign + 2 == text.size()) {
    throw Error(flag + ": " + form);
  }
  // A ROS name has no ':', so one before ':=' starts the message type.
  std::string_view topic_text = text.substr(0, assign);
  std::string type;
  if (const std::size_t colon = topic_text.find(':'); colon != std::string_view::npos) {
    type = std::string(topic_text.substr(colon + 1));
    topic_text = topic_text.substr(0, colon);
    if (type.empty() || topic_text.empty()) throw Error(flag + ": " + form);
  }
  std::string topic;
  try {
    topic = realtime::TopicBus::normalizeTopicName(topic_text);
  } catch (const Error& e) {
    throw Error(flag + ": " + e.what());
  }
  std::string_view value_text = text.substr(assign + 2);
  double time_s = 0.0;
  if (const std::size_t at = value_text.rfind('@'); at != std::string_view::npos) {
    const std::string time_text(value_text.substr(at + 1));
    std::size_t used = 0;
    try {
      time_s = std::stod(time_text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != time_text.size() || !std::isfinite(time_s) || time_s < 0.0) {
      throw Error(fmt::format("{}: TIME '{}' must be simulated seconds >= 0; {}", flag, time_text, form));
    }
    value_text = value_text.substr(0, at);
  }
  nlohmann::json value;
  try {
    value = parseMessageText(value_text, "--pub value");
  } catch (const Error& e) {
    throw Error(flag + ": " + e.what());
  }
  return makeTimedPublication(std::move(topic), std::move(type), value, time_s, flag);
}

RecordSpec parseRecordFlag(std::string_view text) {
  const std::string flag = fmt::format("--record '{}'", text);
  const std::size_t equals = text.find('=');
  if (equals == std::string_view::npos || equals == 0 || equals + 1 == text.size()) {
    throw Error(flag + ": expected TOPIC=FILE.csv, e.g. /robot/joint_states=joint_states.csv");
  }
  RecordSpec spec;
  try {
    spec.topic = realtime::TopicBus::normalizeTopicName(text.substr(0, equals));
  } catch (const Error& e) {
    throw Error(flag + ": " + e.what());
  }
  spec.file = fs::absolute(fs::path(std::string(text.substr(equals + 1)))).lexically_normal();
  return spec;
}

}  // namespace servoloop::node
