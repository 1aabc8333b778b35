#include "servoloop/node/message_json.hpp"

#include <algorithm>
#include <initializer_list>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>

#include "servoloop/params/parameter_store.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::node {

namespace {

using nlohmann::json;

// JSON text for messages and errors; a string that is not UTF-8 (YAML lets
// one through) shows its bad bytes as U+FFFD instead of throwing.
std::string jsonText(const json& value) { return value.dump(-1, ' ', false, json::error_handler_t::replace); }

// Field names of each known type, in ROS order (text and CSV use this order).
const std::map<std::string_view, std::vector<std::string_view>>& fieldTable() {
  static const std::map<std::string_view, std::vector<std::string_view>> table = {
      {std_msgs::Float64::kTypeName, {"data"}},
      {std_msgs::Float64MultiArray::kTypeName, {"data"}},
      {sensor_msgs::JointState::kTypeName, {"stamp", "name", "position", "velocity", "effort"}},
      {control_msgs::JointControllerState::kTypeName,
       {"stamp", "set_point", "process_value", "process_value_dot", "error", "time_step", "command", "p", "i",
        "d", "i_clamp", "antiwindup"}},
      {nav_msgs::Odometry::kTypeName, {"stamp", "frame_id", "child_frame_id", "pose", "twist"}},
      {trajectory_msgs::JointTrajectory::kTypeName, {"stamp", "joint_names", "points"}},
      {control_msgs::JointTrajectoryControllerState::kTypeName, {"stamp", "joint_names", "desired", "actual", "error"}},
  };
  return table;
}

// The fields of a trajectory_msgs/JointTrajectoryPoint, in ROS order.
const std::vector<std::string_view>& pointFields() {
  static const std::vector<std::string_view> fields = {"positions", "velocities", "accelerations", "effort",
                                                       "time_from_start"};
  return fields;
}

std::string describe(const json& value) {
  switch (value.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return value.get<bool>() ? "true" : "false";
    case json::value_t::string: return "string " + jsonText(value);
    case json::value_t::array: return "a list";
    case json::value_t::object: return "an object";
    default: return jsonText(value);
  }
}

std::string joinFields(const std::vector<std::string_view>& fields) {
  std::string joined;
  for (auto field : fields) joined += (joined.empty() ? "" : ", ") + std::string(field);
  return joined;
}

// Reads the fields of one message type from a JSON object, with errors that
// name the type and the field.
class FieldReader {
 public:
  FieldReader(std::string_view type_name, const json& object)
      : FieldReader(type_name, object, fieldTable().at(type_name), "") {}

  // A nested message (e.g. one trajectory point) with its own fields; where
  // names it in errors ("points[2]").
  FieldReader(std::string_view type_name, const json& object, const std::vector<std::string_view>& fields,
              const std::string& where)
      : type_(type_name), prefix_(where.empty() ? "" : where + "."), object_(object) {
    if (!object.is_object()) {
      if (!where.empty()) {
        throw Error(type_ + ": field '" + where + "': expected an object with fields " + joinFields(fields) +
                    ", got " + describe(object));
      }
      fail("", "an object with fields " + joinFields(fields), object);
    }
    for (const auto& [key, value] : object.items()) {
      const bool known = std::find(fields.begin(), fields.end(), key) != fields.end();
      // ROS's Float64MultiArray has a layout field that ros_control never reads.
      const bool ignored = key == "layout" && type_name == std_msgs::Float64MultiArray::kTypeName;
      if (!known && !ignored) {
        throw Error(type_ + ": unknown field '" + prefix_ + key + "'; the fields are: " + joinFields(fields));
      }
    }
  }

  void number(const char* field, double& out) const {
    if (const json* value = find(field)) out = toDouble(field, *value);
  }

  void boolean(const char* field, bool& out) const {
    if (const json* value = find(field)) {
      if (!value->is_boolean()) fail(field, "true or false", *value);
      out = value->get<bool>();
    }
  }

  void numbers(const char* field, std::vector<double>& out) const {
    if (const json* value = find(field)) {
      if (!value->is_array()) fail(field, "a list of numbers", *value);
      out.clear();
      for (std::size_t i = 0; i < value->size(); ++i) {
        out.push_back(toDouble(std::string(field) + "[" + std::to_string(i) + "]", (*value)[i]));
      }
    }
  }

  void strings(const char* field, std::vector<std::string>& out) const {
    if (const json* value = find(field)) {
      if (!value->is_array()) fail(field, "a list of strings", *value);
      out.clear();
      for (std::size_t i = 0; i < value->size(); ++i) {
        const json& item = (*value)[i];
        if (!item.is_string()) fail(std::string(field) + "[" + std::to_string(i) + "]", "a string", item);
        out.push_back(item.get<std::string>());
      }
    }
  }

  void text(const char* field, std::string& out) const {
    if (const json* value = find(field)) {
      if (!value->is_string()) fail(field, "a string", *value);
      out = value->get<std::string>();
    }
  }

  // A nested object of numbers, e.g. pose.position {x, y, z}: `components`
  // names its fields, `out` receives them in that order; missing ones stay.
  void numberObject(const std::string& field, const json* value, std::initializer_list<const char*> components,
                    std::initializer_list<double*> out) const {
    if (value == nullptr) return;
    if (!value->is_object()) fail(field, "an object", *value);
    for (const auto& [key, item] : value->items()) {
      bool known = false;
      for (const char* c : components) known |= key == c;
      if (!known) fail(field + "." + key, "one of the fields of " + field, item);
    }
    auto target = out.begin();
    for (const char* c : components) {
      if (auto it = value->find(c); it != value->end()) **target = toDouble(field + "." + c, *it);
      ++target;
    }
  }

  // A nested object whose fields are objects, e.g. pose {position, orientation}.
  const json* child(const std::string& field, const json* parent, const char* key,
                    std::initializer_list<const char*> keys) const {
    if (parent == nullptr) return nullptr;
    if (!parent->is_object()) fail(field, "an object", *parent);
    for (const auto& [k, item] : parent->items()) {
      bool known = false;
      for (const char* c : keys) known |= k == c;
      if (!known) fail(field + "." + k, "one of the fields of " + field, item);
    }
    auto it = parent->find(key);
    return it == parent->end() ? nullptr : &*it;
  }

  const json* field(const char* name) const { return find(name); }

  [[noreturn]] void fail(const std::string& field, const std::string& expected, const json& got) const {
    const std::string where = field.empty() ? "" : " field '" + prefix_ + field + "':";
    throw Error(type_ + ":" + where + " expected " + expected + ", got " + describe(got));
  }

 private:
  const json* find(const char* field) const {
    auto it = object_.find(field);
    return it == object_.end() ? nullptr : &*it;
  }

  double toDouble(const std::string& field, const json& value) const {
    // null stands for NaN: JSON has no NaN and the serialiser writes it as null.
    if (value.is_null()) return std::numeric_limits<double>::quiet_NaN();
    if (!value.is_number()) fail(field, "a number", value);
    return value.get<double>();
  }

  std::string type_;
  std::string prefix_;  // "points[2]." inside a nested message
  const json& object_;
};

json numberList(const std::vector<double>& values) {
  json list = json::array();
  for (double v : values) list.push_back(v);
  return list;
}

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


// --- JSON per type ------------------------------------------------------------------

json toJson(const std_msgs::Float64& msg) { return json{{"data", msg.data}}; }

json toJson(const std_msgs::Float64MultiArray& msg) { return json{{"data", numberList(msg.data)}}; }

json toJson(const sensor_msgs::JointState& msg) {
  return json{{"stamp", msg.stamp},
              {"name", msg.name},
              {"position", numberList(msg.position)},
              {"velocity", numberList(msg.velocity)},
              {"effort", numberList(msg.effort)}};
}

json toJson(const control_msgs::JointControllerState& msg) {
  return json{{"stamp", msg.stamp},         {"set_point", msg.set_point},
              {"process_value", msg.process_value}, {"process_value_dot", msg.process_value_dot},
              {"error", msg.error},         {"time_step", msg.time_step},
              {"command", msg.command},     {"p", msg.p},
              {"i", msg.i},                 {"d", msg.d},
              {"i_clamp", msg.i_clamp},     {"antiwindup", msg.antiwindup}};
}

json toJson(const nav_msgs::Odometry& msg) {
  return json{{"stamp", msg.stamp},
              {"frame_id", msg.frame_id},
              {"child_frame_id", msg.child_frame_id},
              {"pose",
               {{"position", {{"x", msg.position.x}, {"y", msg.position.y}, {"z", msg.position.z}}},
                {"orientation",
                 {{"x", msg.orientation.x}, {"y", msg.orientation.y}, {"z", msg.orientation.z},
                  {"w", msg.orientation.w}}}}},
              {"twist",
               {{"linear", {{"x", msg.linear.x}, {"y", msg.linear.y}, {"z", msg.linear.z}}},
                {"angular", {{"x", msg.angular.x}, {"y", msg.angular.y}, {"z", msg.angular.z}}}}}};
}

namespace {

json toJson(const trajectory_msgs::JointTrajectoryPoint& point) {
  return json{{"positions", numberList(point.positions)},
              {"velocities", numberList(point.velocities)},
              {"accelerations", numberList(point.accelerations)},
              {"effort", numberList(point.effort)},
              {"time_from_start", point.time_from_start}};
}

void pointFromJson(std::string_view type_name, const json& value, const std::string& where,
                   trajectory_msgs::JointTrajectoryPoint& out) {
  FieldReader reader(type_name, value, pointFields(), where);
  reader.numbers("positions", out.positions);
  reader.numbers("velocities", out.velocities);
  reader.numbers("accelerations", out.accelerations);
  reader.numbers("effort", out.effort);
  reader.number("time_from_start", out.time_from_start);
}

}  // namespace

json toJson(const trajectory_msgs::JointTrajectory& msg) {
  json points = json::array();
  for (const auto& point : msg.points) points.push_back(toJson(point));
  return json{{"stamp", msg.stamp}, {"joint_names", msg.joint_names}, {"points", points}};
}

json toJson(const control_msgs::JointTrajectoryControllerState& msg) {
  return json{{"stamp", msg.stamp},
              {"joint_names", msg.joint_names},
              {"desired", toJson(msg.desired)},
              {"actual", toJson(msg.actual)},
              {"error", toJson(msg.error)}};
}

void fromJson(const json& value, std_msgs::Float64& out) {
  if (value.is_number()) {  // `topic pub /cmd std_msgs/Float64 1.0`
    out.data = value.get<double>();
    return;
  }
  FieldReader reader(std_msgs::Float64::kTypeName, value);
  reader.number("data", out.data);
}

void fromJson(const json& value, std_msgs::Float64MultiArray& out) {
  if (value.is_array()) {  // `topic pub /cmd std_msgs/Float64MultiArray "[1, 2]"`
    FieldReader(std_msgs::Float64MultiArray::kTypeName, json{{"data", value}}).numbers("data", out.data);
    return;
  }
  FieldReader reader(std_msgs::Float64MultiArray::kTypeName, value);
  reader.numbers("data", out.data);
}

void fromJson(const json& value, sensor_msgs::JointState& out) {
  FieldReader reader(sensor_msgs::JointState::kTypeName, value);
  reader.number("stamp", out.stamp);
  reader.strings("name", out.name);
  reader.numbers("position", out.position);
  reader.numbers("velocity", out.velocity);
  reader.numbers("effort", out.effort);
  const auto check_size = [&](const char* field, const std::vector<double>& values) {
    if (!values.empty() && values.size() != out.name.size()) {
      throw Error(std::string(sensor_msgs::JointState::kTypeName) + ": field '" + field + "' has " +
                  std::to_string(values.size()) + " entries but 'name' has " + std::to_string(out.name.size()) +
                  "; give one per joint or none");
    }
  };
  check_size("position", out.position);
  check_size("velocity", out.velocity);
  check_size("effort", out.effort);
}

void fromJson(const json& value, control_msgs::JointControllerState& out) {
  FieldReader reader(control_msgs::JointControllerState::kTypeName, value);
  reader.number("stamp", out.stamp);
  reader.number("set_point", out.set_point);
  reader.number("process_value", out.process_value);
  reader.number("process_value_dot", out.process_value_dot);
  reader.number("error", out.error);
  reader.number("time_step", out.time_step);
  reader.number("command", out.command);
  reader.number("p", out.p);
  reader.number("i", out.i);
  reader.number("d", out.d);
  reader.number("i_clamp", out.i_clamp);
  reader.boolean("antiwindup", out.antiwindup);
}

void fromJson(const json& value, nav_msgs::Odometry& out) {
  FieldReader reader(nav_msgs::Odometry::kTypeName, value);
  reader.number("stamp", out.stamp);
  reader.text("frame_id", out.frame_id);
  reader.text("child_frame_id", out.child_frame_id);
  const json* pose = reader.field("pose");
  reader.numberObject("pose.position", reader.child("pose", pose, "position", {"position", "orientation"}),
                      {"x", "y", "z"}, {&out.position.x, &out.position.y, &out.position.z});
  reader.numberObject("pose.orientation", reader.child("pose", pose, "orientation", {"position", "orientation"}),
                      {"x", "y", "z", "w"},
                      {&out.orientation.x, &out.orientation.y, &out.orientation.z, &out.orientation.w});
  const json* twist = reader.field("twist");
  reader.numberObject("twist.linear", reader.child("twist", twist, "linear", {"linear", "angular"}),
                      {"x", "y", "z"}, {&out.linear.x, &out.linear.y, &out.linear.z});
  reader.numberObject("twist.angular", reader.child("twist", twist, "angular", {"linear", "angular"}),
                      {"x", "y", "z"}, {&out.angular.x, &out.angular.y, &out.angular.z});
}

void fromJson(const json& value, trajectory_msgs::JointTrajectory& out) {
  constexpr std::string_view type = trajectory_msgs::JointTrajectory::kTypeName;
  FieldReader reader(type, value);
  reader.number("stamp", out.stamp);
  reader.strings("joint_names", out.joint_names);
  if (const json* points = reader.field("points")) {
    if (!points->is_array()) reader.fail("points", "a list of points", *points);
    out.points.assign(points->size(), {});
    for (std::size_t i = 0; i < points->size(); ++i) {
      pointFromJson(type, (*points)[i], "points[" + std::to_string(i) + "]", out.points[i]);
    }
  }
}

void fromJson(const json& value, control_msgs::JointTrajectoryControllerState& out) {
  constexpr std::string_view type = control_msgs::JointTrajectoryControllerState::kTypeName;
  FieldReader reader(type, value);
  reader.number("stamp", out.stamp);
  reader.strings("joint_names", out.joint_names);
  if (const json* desired = reader.field("desired")) pointFromJson(type, *desired, "desired", out.desired);
  if (const json* actual = reader.field("actual")) pointFromJson(type, *actual, "actual", out.actual);
  if (const json* error = reader.field("error")) pointFromJson(type, *error, "error", out.error);
}

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
  if (type_name == sensor_msgs::JointState::kTypeName) return decode(sensor_msgs::JointState{});
  if (type_name == control_msgs::JointControllerState::kTypeName) {
    return decode(control_msgs::JointControllerState{});
  }
  if (type_name == nav_msgs::Odometry::kTypeName) return decode(nav_msgs::Odometry{});
  if (type_name == trajectory_msgs::JointTrajectory::kTypeName) return decode(trajectory_msgs::JointTrajectory{});
  if (type_name == control_msgs::JointTrajectoryControllerState::kTypeName) {
    return decode(control_msgs::JointTrajectoryControllerState{});
  }
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
  if (const auto* m = msg.as<sensor_msgs::JointState>()) return toJson(*m);
  if (const auto* m = msg.as<control_msgs::JointControllerState>()) return toJson(*m);
  if (const auto* m = msg.as<nav_msgs::Odometry>()) return toJson(*m);
  if (const auto* m = msg.as<trajectory_msgs::JointTrajectory>()) return toJson(*m);
  if (const auto* m = msg.as<control_msgs::JointTrajectoryControllerState>()) return toJson(*m);
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
