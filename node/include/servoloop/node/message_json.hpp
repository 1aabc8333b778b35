#pragma once
// Conversions of the bus messages (messages.hpp) to and from JSON, to the
// rostopic-style text form and to flattened CSV columns. All non-real-time.
//
// JSON form: one key per ROS field, e.g. {"data": 1.0} or
// {"stamp": 0.5, "name": ["joint1"], "position": [0.1], "velocity": [], "effort": []}.
// Parsing accepts what `rostopic pub` users write: missing fields keep their
// default, integers are accepted for floating-point fields, and single-field
// messages also accept the bare value (`1.0` for std_msgs/Float64, `[1, 2]`
// for std_msgs/Float64MultiArray). Errors throw servoloop::Error naming the
// message type and the field, e.g.
//   std_msgs/Float64: field 'data': expected a number, got string "abc"
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "servoloop/realtime/message_view.hpp"
#include "servoloop/realtime/messages.hpp"
#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/core/number_text.hpp"
#include "servoloop/core/time.hpp"

namespace servoloop::node {

// --- JSON, per type -----------------------------------------------------------
nlohmann::json toJson(const std_msgs::Float64& msg);
nlohmann::json toJson(const std_msgs::Float64MultiArray& msg);
nlohmann::json toJson(const std_msgs::Bool& msg);
nlohmann::json toJson(const diagnostic_msgs::DiagnosticArray& msg);
nlohmann::json toJson(const sensor_msgs::JointState& msg);
nlohmann::json toJson(const control_msgs::JointControllerState& msg);
nlohmann::json toJson(const nav_msgs::Odometry& msg);
nlohmann::json toJson(const trajectory_msgs::JointTrajectory& msg);
nlohmann::json toJson(const control_msgs::JointTrajectoryControllerState& msg);
nlohmann::json toJson(const geometry_msgs::Twist& msg);
nlohmann::json toJson(const tf2_msgs::TFMessage& msg);
nlohmann::json toJson(const gazebo_msgs::ModelStates& msg);
nlohmann::json toJson(const geometry_msgs::WrenchStamped& msg);
nlohmann::json toJson(const sensor_msgs::Imu& msg);
nlohmann::json toJson(const gazebo_msgs::ContactsState& msg);

void fromJson(const nlohmann::json& json, std_msgs::Float64& out);
void fromJson(const nlohmann::json& json, std_msgs::Bool& out);
void fromJson(const nlohmann::json& json, diagnostic_msgs::DiagnosticArray& out);
void fromJson(const nlohmann::json& json, std_msgs::Float64MultiArray& out);
void fromJson(const nlohmann::json& json, sensor_msgs::JointState& out);
void fromJson(const nlohmann::json& json, control_msgs::JointControllerState& out);
void fromJson(const nlohmann::json& json, nav_msgs::Odometry& out);
void fromJson(const nlohmann::json& json, trajectory_msgs::JointTrajectory& out);
void fromJson(const nlohmann::json& json, control_msgs::JointTrajectoryControllerState& out);
void fromJson(const nlohmann::json& json, geometry_msgs::Twist& out);
void fromJson(const nlohmann::json& json, tf2_msgs::TFMessage& out);
void fromJson(const nlohmann::json& json, gazebo_msgs::ModelStates& out);
void fromJson(const nlohmann::json& json, geometry_msgs::WrenchStamped& out);
void fromJson(const nlohmann::json& json, sensor_msgs::Imu& out);
void fromJson(const nlohmann::json& json, gazebo_msgs::ContactsState& out);

template <class Msg>
Msg messageFromJson(const nlohmann::json& json) {
  Msg msg;
  fromJson(json, msg);
  return msg;
}

// --- YAML / text input ----------------------------------------------------------
// YAML value → JSON, scalars typed the way YAML (and rosparam) types them:
// 1 → integer, 1.0 → number, true → boolean, "1" (quoted) → string, ~ → null.
nlohmann::json yamlToJson(const YAML::Node& node);

// Parses the text a user gives `topic pub`: YAML ("data: 1.0", "{data: 1.0}",
// "[1, 2]", "1.0") or JSON. source_name prefixes syntax errors.
nlohmann::json parseMessageText(std::string_view text, std::string_view source_name = "message");

// Throws servoloop::Error when a command message (std_msgs/Float64,
// Float64MultiArray, geometry_msgs/Twist or trajectory_msgs/JointTrajectory, given as JSON) holds
// NaN (null) or an infinite value, naming the field: a command from a user or
// client must be a finite number. Other types pass.
void requireFiniteCommand(std::string_view type_name, const nlohmann::json& msg);

// --- Type-erased helpers (for the IPC server and the recorder) --------------
// Message types this module can convert; knownMessageTypes() is sorted.
bool isKnownMessageType(std::string_view type_name);
std::vector<std::string> knownMessageTypes();

// The rostopic-style text of a message given as JSON, fields in ROS order for
// known types: "data: 1.0", or one "field: value" line per field with lists
// inline ("position: [0.1, 0.2]"). No trailing "---" separator.
std::string messageToText(std::string_view type_name, const nlohmann::json& msg);

template <class Msg>
std::string toText(const Msg& msg) {
  return messageToText(Msg::kTypeName, toJson(msg));
}

// --- The topic bus in JSON (topic pub/echo, the recorder) ------------------------
// A message of any known type as JSON; throws servoloop::Error naming the type
// for a type that has no JSON form (one only a plugin knows).
nlohmann::json toJson(const realtime::MessageView& msg);

// msg read as type_name and written back in full (every field, defaults
// filled in). Throws servoloop::Error naming the type and the field, or the
// known types for an unknown one.
nlohmann::json normalizeMessage(std::string_view type_name, const nlohmann::json& msg);

// A subscriber that takes any message type in its JSON form, with the time it
// was published.
using JsonCallback = std::function<void(Time stamp, const nlohmann::json& msg)>;

// TopicBus::subscribeAny with the message converted to JSON (once per message
// and subscriber). The topic need not exist yet.
[[nodiscard]] realtime::Subscription subscribeJson(realtime::TopicBus& bus, std::string_view topic,
                                                   JsonCallback callback);

// Publishes a message given as JSON. type_name may be empty when the topic
// already has a type; if given it must match, and it creates the topic if
// needed. Errors name the topic and the field.
void publishJson(realtime::TopicBus& bus, std::string_view topic, const nlohmann::json& msg,
                 std::string_view type_name = {});

// Throws servoloop::Error naming the topic when it exists with a type other
// than type_name (publishJson's check, for callers that check ahead).
void requireTopicType(const realtime::TopicBus& bus, const std::string& topic, std::string_view type_name);

// Flattened CSV for recording, first column "time" (seconds):
//   std_msgs/Float64            time,data
//   std_msgs/Float64MultiArray  time,data[0],data[1],...
//   sensor_msgs/JointState      time,<joint>.position,<joint>.velocity,<joint>.effort per joint
//   others                      time,<field>,... with lists as <field>[i]
// The header depends on the message (joint names, array length); a recorder
// writes it from the first message. Values print in shortest round-trip form.
std::string csvHeader(std::string_view type_name, const nlohmann::json& msg);
std::string csvRow(std::string_view type_name, Time stamp, const nlohmann::json& msg);

template <class Msg>
std::string csvHeader(const Msg& msg) {
  return csvHeader(Msg::kTypeName, toJson(msg));
}
template <class Msg>
std::string csvRow(const Msg& msg, Time stamp) {
  return csvRow(Msg::kTypeName, stamp, toJson(msg));
}


}  // namespace servoloop::node
