#pragma once
// Internal to node/: what message_json.cpp (text, CSV, the bus in JSON) and
// message_json_types.cpp (each type's JSON) share: the field order of each
// type and the reader of a JSON object's fields with errors that name the
// type and the field.
#include <algorithm>
#include <initializer_list>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "servoloop/core/errors.hpp"
#include "servoloop/realtime/messages.hpp"

namespace servoloop::node::detail {

using nlohmann::json;


// JSON text for messages and errors; a string that is not UTF-8 (YAML lets
// one through) shows its bad bytes as U+FFFD instead of throwing.
inline std::string jsonText(const json& value) { return value.dump(-1, ' ', false, json::error_handler_t::replace); }

// Field names of each known type, in ROS order (text and CSV use this order).
inline const std::map<std::string_view, std::vector<std::string_view>>& fieldTable() {
  static const std::map<std::string_view, std::vector<std::string_view>> table = {
      {std_msgs::Float64::kTypeName, {"data"}},
      {std_msgs::Float64MultiArray::kTypeName, {"data"}},
      {std_msgs::Bool::kTypeName, {"data"}},
      {diagnostic_msgs::DiagnosticArray::kTypeName, {"stamp", "status"}},
      {sensor_msgs::JointState::kTypeName, {"stamp", "name", "position", "velocity", "effort"}},
      {control_msgs::JointControllerState::kTypeName,
       {"stamp", "set_point", "process_value", "process_value_dot", "error", "time_step", "command", "p", "i",
        "d", "i_clamp", "antiwindup"}},
      {nav_msgs::Odometry::kTypeName, {"stamp", "frame_id", "child_frame_id", "pose", "twist"}},
      {trajectory_msgs::JointTrajectory::kTypeName, {"stamp", "joint_names", "points"}},
      {control_msgs::JointTrajectoryControllerState::kTypeName, {"stamp", "joint_names", "desired", "actual", "error"}},
      {geometry_msgs::Twist::kTypeName, {"linear", "angular"}},
      {tf2_msgs::TFMessage::kTypeName, {"transforms"}},
      {gazebo_msgs::ModelStates::kTypeName, {"name", "pose", "twist"}},
      {geometry_msgs::WrenchStamped::kTypeName, {"stamp", "frame_id", "wrench"}},
      {sensor_msgs::Imu::kTypeName,
       {"stamp", "frame_id", "orientation", "orientation_covariance", "angular_velocity",
        "angular_velocity_covariance", "linear_acceleration", "linear_acceleration_covariance"}},
      {gazebo_msgs::ContactsState::kTypeName, {"stamp", "frame_id", "states"}},
  };
  return table;
}

// The fields of a trajectory_msgs/JointTrajectoryPoint, in ROS order.
inline const std::vector<std::string_view>& pointFields() {
  static const std::vector<std::string_view> fields = {"positions", "velocities", "accelerations", "effort",
                                                       "time_from_start"};
  return fields;
}

inline std::string describe(const json& value) {
  switch (value.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return value.get<bool>() ? "true" : "false";
    case json::value_t::string: return "string " + jsonText(value);
    case json::value_t::array: return "a list";
    case json::value_t::object: return "an object";
    default: return jsonText(value);
  }
}

inline std::string joinFields(const std::vector<std::string_view>& fields) {
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

  // A nested list of exactly `size` numbers, e.g. pose.covariance.
  void fixedNumbers(const std::string& field, const json* value, double* out, std::size_t size) const {
    if (value == nullptr) return;
    if (!value->is_array() || value->size() != size) {
      fail(field, "a list of " + std::to_string(size) + " numbers", *value);
    }
    for (std::size_t i = 0; i < size; ++i) out[i] = toDouble(field + "[" + std::to_string(i) + "]", (*value)[i]);
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

inline json numberList(const std::vector<double>& values) {
  json list = json::array();
  for (double v : values) list.push_back(v);
  return list;
}

}  // namespace servoloop::node::detail
