#include "servoloop/node/message_json.hpp"

#include <algorithm>
#include <initializer_list>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>

#include "message_json_detail.hpp"
#include "servoloop/params/parameter_store.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::node {

namespace {

using nlohmann::json;
using namespace detail;

std::string textOf(const json& value, bool quote_strings);

std::string inlineList(const json& list) {
  std::string text = "[";
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (i > 0) text += ", ";
    text += textOf(list[i], false);
  }
  return text + "]";
}

std::string textOf(const json& value, bool quote_strings) {
  switch (value.type()) {
    case json::value_t::null: return "nan";
    case json::value_t::boolean: return value.get<bool>() ? "True" : "False";
    case json::value_t::number_float: return formatDouble(value.get<double>());
    case json::value_t::number_integer:
    case json::value_t::number_unsigned: return jsonText(value);
    case json::value_t::string: {
      // jsonText shows bytes that are not UTF-8 as U+FFFD; unquoted, the quotes go.
      const std::string quoted = jsonText(value);
      return quote_strings ? quoted : quoted.substr(1, quoted.size() - 2);
    }
    case json::value_t::array: return inlineList(value);
    default: return jsonText(value);
  }
}

// The type of a message's nested field that has a field order of its own
// (a trajectory point), or "".
constexpr std::string_view kPointType = "trajectory_msgs/JointTrajectoryPoint";
std::string_view nestedType(std::string_view type_name, std::string_view key) {
  if (type_name == control_msgs::JointTrajectoryControllerState::kTypeName &&
      (key == "desired" || key == "actual" || key == "error")) {
    return kPointType;
  }
  if (type_name == trajectory_msgs::JointTrajectory::kTypeName && key == "points") return kPointType;
  return {};
}

// Keys of an object: the type's known fields in ROS order, then any others.
std::vector<std::string> orderedKeys(std::string_view type_name, const json& object) {
  std::vector<std::string> keys;
  const auto& fields = type_name == kPointType ? pointFields() : std::vector<std::string_view>{};
  if (auto it = fieldTable().find(type_name); it != fieldTable().end()) {
    for (auto field : it->second) {
      if (object.contains(std::string(field))) keys.emplace_back(field);
    }
  }
  for (auto field : fields) {
    if (object.contains(std::string(field))) keys.emplace_back(field);
  }
  for (const auto& [key, value] : object.items()) {
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  }
  return keys;
}

void appendText(std::string& out, std::string_view type_name, const json& object, int indent) {
  for (const std::string& key : orderedKeys(type_name, object)) {
    const json& value = object.at(key);
    out += std::string(static_cast<std::size_t>(indent), ' ') + key + ":";
    if (value.is_object()) {
      out += "\n";
      appendText(out, nestedType(type_name, key), value, indent + 2);
    } else {
      out += " " + textOf(value, true) + "\n";
    }
  }
}

std::string csvCell(const json& value) {
  switch (value.type()) {
    case json::value_t::null: return "nan";
    case json::value_t::boolean: return value.get<bool>() ? "1" : "0";
    case json::value_t::number_float: return formatDouble(value.get<double>());
    case json::value_t::string: {
      const std::string text = value.get<std::string>();
      if (text.find_first_of(",\"\n") == std::string::npos) return text;
      std::string quoted = "\"";
      for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
      return quoted + "\"";
    }
    default: return jsonText(value);
  }
}

// Flattened (column, value) pairs of a message, without the time column.
std::vector<std::pair<std::string, std::string>> flatten(std::string_view type_name, const json& msg) {
  std::vector<std::pair<std::string, std::string>> columns;
  if (type_name == sensor_msgs::JointState::kTypeName && msg.is_object()) {
    const json names = msg.value("name", json::array());
    for (std::size_t j = 0; j < names.size(); ++j) {
      const std::string joint = names[j].is_string() ? names[j].get<std::string>() : std::to_string(j);
      for (const char* field : {"position", "velocity", "effort"}) {
        const json values = msg.value(field, json::array());
        columns.emplace_back(joint + "." + field, j < values.size() ? csvCell(values[j]) : "");
      }
    }
    return columns;
  }
  struct Walker {
    std::vector<std::pair<std::string, std::string>>& columns;
    void walk(const std::string& prefix, std::string_view type, const json& value, std::string_view item_type = {}) {
      if (value.is_object()) {
        for (const std::string& key : orderedKeys(type, value)) {
          // The time column already carries the stamp.
          if (prefix.empty() && key == "stamp") continue;
          const std::string_view nested = nestedType(type, key);
          const json& field = value.at(key);
          walk(prefix.empty() ? key : prefix + "." + key, field.is_array() ? "" : nested, field,
               field.is_array() ? nested : "");
        }
      } else if (value.is_array()) {
        for (std::size_t i = 0; i < value.size(); ++i) {
          walk(prefix + "[" + std::to_string(i) + "]", item_type, value[i]);
        }
      } else {
        columns.emplace_back(prefix.empty() ? "value" : prefix, csvCell(value));
      }
    }
  };
  Walker{columns}.walk("", type_name, msg);
  return columns;
}

}  // namespace


// --- YAML / text input ----------------------------------------------------------------

json yamlToJson(const YAML::Node& node) {
  switch (params::paramTypeOf(node)) {
    case params::ParamType::null: return nullptr;
    case params::ParamType::map: {
      json object = json::object();
      for (const auto& entry : node) object[entry.first.Scalar()] = yamlToJson(entry.second);
      return object;
    }
    case params::ParamType::list: {
      json list = json::array();
      for (const auto& item : node) list.push_back(yamlToJson(item));
      return list;
    }
    case params::ParamType::boolean: return node.as<bool>();
    case params::ParamType::integer: return params::paramIntegerValue(node);
    case params::ParamType::floating: return params::paramDoubleValue(node);
    case params::ParamType::string: return node.Scalar();
  }
  return nullptr;
}

namespace {

// What is wrong with a YAML number that no JSON (and so no IPC request) can
// carry: JSON has no NaN or infinity, and nlohmann writes them as null, which
// the node would report as "expected a number, got null". "" when finite.
std::string nonFiniteNumberProblem(const YAML::Node& scalar) {
  if (params::paramTypeOf(scalar) != params::ParamType::floating) return "";
  const double value = params::paramDoubleValue(scalar);
  if (std::isfinite(value)) return "";
  const std::string& text = scalar.Scalar();
  std::string body = text;
  if (!body.empty() && (body.front() == '-' || body.front() == '+')) body.erase(0, 1);
  std::string lower = body;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  if (lower == ".nan" || std::isnan(value)) return text + " is not a number";
  if (lower == ".inf") return text + " is infinite";
  return text + " is out of range of a double (the largest is 1.8e308)";
}

// Refuses NaN, .inf and numbers past a double's range anywhere in a message
// typed by a user, naming the field, before they become null in JSON.
void requireRepresentableNumbers(const YAML::Node& document, std::string_view source_name) {
  std::vector<std::pair<YAML::Node, std::string>> pending{{document, ""}};
  while (!pending.empty()) {
    const auto [node, path] = pending.back();
    pending.pop_back();
    if (node.IsMap()) {
      for (const auto& entry : node) {
        const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "?";
        pending.emplace_back(entry.second, path.empty() ? key : path + "." + key);
      }
    } else if (node.IsSequence()) {
      for (std::size_t i = 0; i < node.size(); ++i) pending.emplace_back(node[i], path + "[" + std::to_string(i) + "]");
    } else if (node.IsScalar()) {
      const std::string problem = nonFiniteNumberProblem(node);
      if (problem.empty()) continue;
      throw Error(std::string(source_name) + ": " + (path.empty() ? std::string("the value") : "field '" + path + "'") +
                  ": " + problem + "; a message holds finite numbers only (JSON, which carries it to the node, has "
                  "no NaN or infinity)");
    }
  }
}

}  // namespace

json parseMessageText(std::string_view text, std::string_view source_name) {
  YAML::Node node;
  try {
    node = YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    const std::string where = e.mark.is_null() ? "" : " (line " + std::to_string(e.mark.line + 1) + ", column " +
                                                          std::to_string(e.mark.column + 1) + ")";
    throw Error(std::string(source_name) + ": cannot read '" + std::string(text) + "'" + where + ": " + e.msg +
                "; write YAML such as \"data: 1.0\" or JSON such as {\"data\": 1.0}");
  }
  params::checkYamlDocument(node, source_name);
  if (!node.IsDefined() || node.IsNull()) return json::object();  // all fields default
  requireRepresentableNumbers(node, source_name);
  return yamlToJson(node);
}

void requireFiniteCommand(std::string_view type_name, const json& msg) {
  std::vector<double> values;
  if (type_name == std_msgs::Float64::kTypeName) {
    values.push_back(messageFromJson<std_msgs::Float64>(msg).data);
  } else if (type_name == std_msgs::Float64MultiArray::kTypeName) {
    values = messageFromJson<std_msgs::Float64MultiArray>(msg).data;
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (std::isfinite(values[i])) continue;
    const std::string where = type_name == std_msgs::Float64::kTypeName ? "" : "[" + std::to_string(i) + "]";
    throw Error(std::string(type_name) + ": data" + where + " is " + formatDouble(values[i]) +
                "; a command must be a finite number");
  }
  if (type_name == geometry_msgs::Twist::kTypeName) {
    const auto twist = messageFromJson<geometry_msgs::Twist>(msg);
    const double values[] = {twist.linear.x, twist.linear.y, twist.linear.z,
                             twist.angular.x, twist.angular.y, twist.angular.z};
    const char* names[] = {"linear.x", "linear.y", "linear.z", "angular.x", "angular.y", "angular.z"};
    for (std::size_t i = 0; i < 6; ++i) {
      if (!std::isfinite(values[i])) {
        throw Error(std::string(type_name) + ": " + names[i] + " is " + formatDouble(values[i]) +
                    "; a command must be a finite number");
      }
    }
  }
  if (type_name == trajectory_msgs::JointTrajectory::kTypeName) {
    const auto trajectory = messageFromJson<trajectory_msgs::JointTrajectory>(msg);
    const auto require = [&](double value, const std::string& field) {
      if (!std::isfinite(value)) {
        throw Error(std::string(type_name) + ": " + field + " is " + formatDouble(value) +
                    "; a trajectory must hold finite numbers");
      }
    };
    require(trajectory.stamp, "stamp");
    for (std::size_t i = 0; i < trajectory.points.size(); ++i) {
      const auto& point = trajectory.points[i];
      const std::string where = "points[" + std::to_string(i) + "].";
      const auto require_all = [&](const std::vector<double>& list, const char* field) {
        for (std::size_t j = 0; j < list.size(); ++j) require(list[j], where + field + "[" + std::to_string(j) + "]");
      };
      require_all(point.positions, "positions");
      require_all(point.velocities, "velocities");
      require_all(point.accelerations, "accelerations");
      require_all(point.effort, "effort");
      require(point.time_from_start, where + "time_from_start");
    }
  }
}

// --- Type-erased helpers --------------------------------------------------------------

bool isKnownMessageType(std::string_view type_name) { return fieldTable().contains(type_name); }

std::vector<std::string> knownMessageTypes() {
  std::vector<std::string> names;
  for (const auto& [name, fields] : fieldTable()) names.emplace_back(name);
  return names;
}

std::string messageToText(std::string_view type_name, const json& msg) {
  if (!msg.is_object()) return textOf(msg, true) + "\n";
  std::string text;
  appendText(text, type_name, msg, 0);
  return text;
}

// --- The topic bus in JSON -----------------------------------------------------------

namespace {

// Calls fn with a MessageView of `value` decoded as type_name.
template <class Fn>
void withMessageFromJson(std::string_view type_name, const json& value, Fn&& fn) {
  const auto decode = [&](auto msg) {
    fromJson(value, msg);
    fn(realtime::MessageView{decltype(msg)::kTypeName, &msg});
  };
  if (type_name == std_msgs::Float64::kTypeName) return decode(std_msgs::Float64{});
  if (type_name == std_msgs::Float64MultiArray::kTypeName) return decode(std_msgs::Float64MultiArray{});
  if (type_name == std_msgs::Bool::kTypeName) return decode(std_msgs::Bool{});
  if (type_name == diagnostic_msgs::DiagnosticArray::kTypeName) return decode(diagnostic_msgs::DiagnosticArray{});
  if (type_name == sensor_msgs::JointState::kTypeName) return decode(sensor_msgs::JointState{});
  if (type_name == control_msgs::JointControllerState::kTypeName) {
    return decode(control_msgs::JointControllerState{});
  }
  if (type_name == nav_msgs::Odometry::kTypeName) return decode(nav_msgs::Odometry{});
  if (type_name == trajectory_msgs::JointTrajectory::kTypeName) return decode(trajectory_msgs::JointTrajectory{});
  if (type_name == control_msgs::JointTrajectoryControllerState::kTypeName) {
    return decode(control_msgs::JointTrajectoryControllerState{});
  }
  if (type_name == geometry_msgs::Twist::kTypeName) return decode(geometry_msgs::Twist{});
  if (type_name == tf2_msgs::TFMessage::kTypeName) return decode(tf2_msgs::TFMessage{});
  if (type_name == gazebo_msgs::ModelStates::kTypeName) return decode(gazebo_msgs::ModelStates{});
  if (type_name == geometry_msgs::WrenchStamped::kTypeName) return decode(geometry_msgs::WrenchStamped{});
  if (type_name == sensor_msgs::Imu::kTypeName) return decode(sensor_msgs::Imu{});
  if (type_name == gazebo_msgs::ContactsState::kTypeName) return decode(gazebo_msgs::ContactsState{});
  std::string known;
  for (const std::string& type : knownMessageTypes()) known += (known.empty() ? "" : ", ") + type;
  throw Error("unknown message type '" + std::string(type_name) + "'; known types: " + known);
}

std::string topicNames(const realtime::TopicBus& bus) {
  const auto topics = bus.list();
  if (topics.empty()) return "there are no topics yet";
  std::string names = "topics are: ";
  for (std::size_t i = 0; i < topics.size(); ++i) names += (i == 0 ? "" : ", ") + topics[i].name;
  return names;
}

}  // namespace

json toJson(const realtime::MessageView& msg) {
  if (const auto* m = msg.as<std_msgs::Float64>()) return toJson(*m);
  if (const auto* m = msg.as<std_msgs::Float64MultiArray>()) return toJson(*m);
  if (const auto* m = msg.as<std_msgs::Bool>()) return toJson(*m);
  if (const auto* m = msg.as<diagnostic_msgs::DiagnosticArray>()) return toJson(*m);
  if (const auto* m = msg.as<sensor_msgs::JointState>()) return toJson(*m);
  if (const auto* m = msg.as<control_msgs::JointControllerState>()) return toJson(*m);
  if (const auto* m = msg.as<nav_msgs::Odometry>()) return toJson(*m);
  if (const auto* m = msg.as<trajectory_msgs::JointTrajectory>()) return toJson(*m);
  if (const auto* m = msg.as<control_msgs::JointTrajectoryControllerState>()) return toJson(*m);
  if (const auto* m = msg.as<geometry_msgs::Twist>()) return toJson(*m);
  if (const auto* m = msg.as<tf2_msgs::TFMessage>()) return toJson(*m);
  if (const auto* m = msg.as<gazebo_msgs::ModelStates>()) return toJson(*m);
  if (const auto* m = msg.as<geometry_msgs::WrenchStamped>()) return toJson(*m);
  if (const auto* m = msg.as<sensor_msgs::Imu>()) return toJson(*m);
  if (const auto* m = msg.as<gazebo_msgs::ContactsState>()) return toJson(*m);
  throw Error("message type '" + std::string(msg.type) + "' has no JSON form");
}

void requireTopicType(const realtime::TopicBus& bus, const std::string& topic, std::string_view type_name) {
  if (!bus.hasTopic(topic)) return;
  const std::string existing = bus.typeOf(topic);
  if (!existing.empty() && existing != type_name) {
    throw Error("topic '" + topic + "' carries " + existing + ", not " + std::string(type_name) + "; use " + existing +
                " on it or pick another topic name");
  }
}

json normalizeMessage(std::string_view type_name, const json& msg) {
  json normalized;
  withMessageFromJson(type_name, msg, [&](const realtime::MessageView& view) { normalized = toJson(view); });
  return normalized;
}

realtime::Subscription subscribeJson(realtime::TopicBus& bus, std::string_view topic, JsonCallback callback) {
  return bus.subscribeAny(topic, [callback = std::move(callback)](Time stamp, const realtime::MessageView& msg) {
    callback(stamp, toJson(msg));
  });
}

void publishJson(realtime::TopicBus& bus, std::string_view topic, const json& msg, std::string_view type_name) {
  const std::string name = realtime::TopicBus::normalizeTopicName(topic);
  std::string type(type_name);
  if (type.empty()) {
    if (!bus.hasTopic(name)) {
      throw Error("no topic '" + name + "' (" + topicNames(bus) +
                  "); give the message type to create it, e.g. std_msgs/Float64");
    }
    type = bus.typeOf(name);
    if (type.empty()) {
      throw Error("topic '" + name +
                  "' has no type yet (only untyped subscribers know it); give the message type to publish on it");
    }
  } else {
    requireTopicType(bus, name, type);
  }
  try {
    requireFiniteCommand(type, msg);
    withMessageFromJson(type, msg, [&](const realtime::MessageView& view) { bus.publishView(name, view); });
  } catch (const Error& e) {
    const std::string what = e.what();
    if (what.starts_with("unknown message type")) {
      throw Error("unknown message type '" + type + "' for topic '" + name + "'" + what.substr(what.find(';')));
    }
    if (what.starts_with("topic '")) throw;
    throw Error("topic '" + name + "': " + what);
  }
}

std::string csvHeader(std::string_view type_name, const json& msg) {
  std::string header = "time";
  for (const auto& [column, value] : flatten(type_name, msg)) header += "," + column;
  return header;
}

std::string csvRow(std::string_view type_name, Time stamp, const json& msg) {
  std::string row = formatDouble(stamp.seconds);
  for (const auto& [column, value] : flatten(type_name, msg)) row += "," + value;
  return row;
}

}  // namespace servoloop::node
