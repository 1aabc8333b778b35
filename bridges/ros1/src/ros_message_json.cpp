#include "ros_message_json.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <memory>

#include <control_msgs/JointControllerState.h>
#include <control_msgs/JointTrajectoryControllerState.h>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <gazebo_msgs/ContactsState.h>
#include <gazebo_msgs/ModelStates.h>
#include <geometry_msgs/Twist.h>
#include <geometry_msgs/WrenchStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/console.h>
#include <ros/serialization.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Bool.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Float64MultiArray.h>
#include <tf2_msgs/TFMessage.h>
#include <trajectory_msgs/JointTrajectory.h>

#include <stdexcept>

namespace servoloop::ros1 {

using nlohmann::json;

namespace {

// The conversions declared in the header (the action bridge and the Gazebo
// services use them too) are overloads of the ones below.
using ros1::fromJson;
using ros1::toJson;

// --- JSON → ROS ------------------------------------------------------------------
double number(const json& parent, const char* key) {
  const auto it = parent.find(key);
  if (it == parent.end()) return 0.0;
  if (it->is_null()) return std::numeric_limits<double>::quiet_NaN();
  return it->get<double>();
}

std::vector<double> numbers(const json& parent, const char* key) {
  std::vector<double> out;
  const auto it = parent.find(key);
  if (it == parent.end() || !it->is_array()) return out;
  out.reserve(it->size());
  for (const json& value : *it) {
    out.push_back(value.is_null() ? std::numeric_limits<double>::quiet_NaN() : value.get<double>());
  }
  return out;
}

std::vector<std::string> strings(const json& parent, const char* key) {
  const auto it = parent.find(key);
  if (it == parent.end() || !it->is_array()) return {};
  return it->get<std::vector<std::string>>();
}

std::string text(const json& parent, const char* key) {
  const auto it = parent.find(key);
  return it != parent.end() && it->is_string() ? it->get<std::string>() : std::string();
}

const json& child(const json& parent, const char* key) {
  static const json empty = json::object();
  const auto it = parent.find(key);
  return it != parent.end() && it->is_object() ? *it : empty;
}

ros::Time stampFrom(const json& parent) {
  const double seconds = number(parent, "stamp");
  return std::isfinite(seconds) && seconds >= 0.0 ? ros::Time(seconds) : ros::Time();
}

// --- ROS → JSON -------------------------------------------------------------------
json value(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

json values(const std::vector<double>& xs) {
  json out = json::array();
  for (double x : xs) out.push_back(value(x));
  return out;
}

// Whole nanoseconds divided once: the double nearest to the decimal stamp
// (3.131 s, not 3.1310000000000002), as the node writes its stamps.
double seconds(const ros::Time& time) {
  return (static_cast<double>(time.sec) * 1e9 + static_cast<double>(time.nsec)) / 1e9;
}
double seconds(const ros::Duration& duration) {
  return (static_cast<double>(duration.sec) * 1e9 + static_cast<double>(duration.nsec)) / 1e9;
}

// --- per type ---------------------------------------------------------------------
void fromJson(const json& j, std_msgs::Float64& m) { m.data = j.is_object() ? number(j, "data") : j.get<double>(); }
json toJson(const std_msgs::Float64& m) { return {{"data", value(m.data)}}; }

void fromJson(const json& j, std_msgs::Bool& m) {
  m.data = j.is_object() ? j.value("data", false) : j.get<bool>();
}
json toJson(const std_msgs::Bool& m) { return {{"data", static_cast<bool>(m.data)}}; }

void fromJson(const json& j, std_msgs::Float64MultiArray& m) {
  m.data = j.is_array() ? numbers(json{{"data", j}}, "data") : numbers(j, "data");
}
json toJson(const std_msgs::Float64MultiArray& m) { return {{"data", values(m.data)}}; }

void fromJson(const json& j, sensor_msgs::JointState& m) {
  m.header.stamp = stampFrom(j);
  m.name = strings(j, "name");
  m.position = numbers(j, "position");
  m.velocity = numbers(j, "velocity");
  m.effort = numbers(j, "effort");
}
json toJson(const sensor_msgs::JointState& m) {
  return {{"stamp", seconds(m.header.stamp)}, {"name", m.name}, {"position", values(m.position)},
          {"velocity", values(m.velocity)}, {"effort", values(m.effort)}};
}

void fromJson(const json& j, control_msgs::JointControllerState& m) {
  m.header.stamp = stampFrom(j);
  m.set_point = number(j, "set_point");
  m.process_value = number(j, "process_value");
  m.process_value_dot = number(j, "process_value_dot");
  m.error = number(j, "error");
  m.time_step = number(j, "time_step");
  m.command = number(j, "command");
  m.p = number(j, "p");
  m.i = number(j, "i");
  m.d = number(j, "d");
  m.i_clamp = number(j, "i_clamp");
  m.antiwindup = j.value("antiwindup", false);
}
json toJson(const control_msgs::JointControllerState& m) {
  return {{"stamp", seconds(m.header.stamp)}, {"set_point", value(m.set_point)},
          {"process_value", value(m.process_value)}, {"process_value_dot", value(m.process_value_dot)},
          {"error", value(m.error)}, {"time_step", value(m.time_step)}, {"command", value(m.command)},
          {"p", value(m.p)}, {"i", value(m.i)}, {"d", value(m.d)}, {"i_clamp", value(m.i_clamp)},
          {"antiwindup", static_cast<bool>(m.antiwindup)}};
}

// geometry_msgs' x, y, z messages (Vector3, Point).
template <class Xyz>
void xyzFromJson(const json& j, Xyz& v) {
  v.x = number(j, "x");
  v.y = number(j, "y");
  v.z = number(j, "z");
}
template <class Xyz>
json xyzToJson(const Xyz& v) {
  return {{"x", value(v.x)}, {"y", value(v.y)}, {"z", value(v.z)}};
}
void fromJson(const json& j, geometry_msgs::Vector3& v) { xyzFromJson(j, v); }
json toJson(const geometry_msgs::Vector3& v) { return xyzToJson(v); }
void fromJson(const json& j, geometry_msgs::Point& v) { xyzFromJson(j, v); }
json toJson(const geometry_msgs::Point& v) { return xyzToJson(v); }
void fromJson(const json& j, geometry_msgs::Quaternion& q) {
  q.x = number(j, "x");
  q.y = number(j, "y");
  q.z = number(j, "z");
  q.w = j.contains("w") ? number(j, "w") : 1.0;
}
json toJson(const geometry_msgs::Quaternion& q) {
  return {{"x", value(q.x)}, {"y", value(q.y)}, {"z", value(q.z)}, {"w", value(q.w)}};
}

template <std::size_t N>
void covarianceFrom(const json& j, boost::array<double, N>& out, const char* key = "covariance") {
  const std::vector<double> xs = numbers(j, key);
  for (std::size_t i = 0; i < N; ++i) out[i] = i < xs.size() ? xs[i] : 0.0;
}
template <std::size_t N>
json covarianceOf(const boost::array<double, N>& xs) {
  return values(std::vector<double>(xs.begin(), xs.end()));
}

void fromJson(const json& j, tf2_msgs::TFMessage& m) {
  m.transforms.clear();
  const auto it = j.find("transforms");
  if (it == j.end() || !it->is_array()) return;
  for (const json& t : *it) {
    geometry_msgs::TransformStamped& out = m.transforms.emplace_back();
    out.header.stamp = stampFrom(t);
    out.header.frame_id = text(t, "frame_id");
    out.child_frame_id = text(t, "child_frame_id");
    fromJson(child(t, "translation"), out.transform.translation);
    fromJson(child(t, "rotation"), out.transform.rotation);
  }
}
json toJson(const tf2_msgs::TFMessage& m) {
  json transforms = json::array();
  for (const auto& t : m.transforms) {
    transforms.push_back({{"stamp", seconds(t.header.stamp)}, {"frame_id", t.header.frame_id},
                          {"child_frame_id", t.child_frame_id}, {"translation", toJson(t.transform.translation)},
                          {"rotation", toJson(t.transform.rotation)}});
  }
  return {{"transforms", std::move(transforms)}};
}

void fromJson(const json& j, diagnostic_msgs::DiagnosticArray& m) {
  m.header.stamp = stampFrom(j);
  m.status.clear();
  const auto it = j.find("status");
  if (it == j.end() || !it->is_array()) return;
  for (const json& s : *it) {
    diagnostic_msgs::DiagnosticStatus& out = m.status.emplace_back();
    out.level = static_cast<std::int8_t>(s.value("level", 0));
    out.name = text(s, "name");
    out.message = text(s, "message");
    out.hardware_id = text(s, "hardware_id");
    if (const auto kv = s.find("values"); kv != s.end() && kv->is_array()) {
      for (const json& pair : *kv) {
        diagnostic_msgs::KeyValue& entry = out.values.emplace_back();
        entry.key = text(pair, "key");
        entry.value = text(pair, "value");
      }
    }
  }
}
json toJson(const diagnostic_msgs::DiagnosticArray& m) {
  json status = json::array();
  for (const auto& s : m.status) {
    json kv = json::array();
    for (const auto& pair : s.values) kv.push_back({{"key", pair.key}, {"value", pair.value}});
    status.push_back({{"level", static_cast<int>(s.level)}, {"name", s.name}, {"message", s.message},
                      {"hardware_id", s.hardware_id}, {"values", std::move(kv)}});
  }
  return {{"stamp", seconds(m.header.stamp)}, {"status", std::move(status)}};
}

// No header: Gazebo's model states carry no stamp. One pose and one twist per
// name, in the world frame and axes.
void fromJson(const json& j, gazebo_msgs::ModelStates& m) {
  m.name = strings(j, "name");
  m.pose.clear();
  m.twist.clear();
  if (const auto it = j.find("pose"); it != j.end() && it->is_array()) {
    for (const json& pose : *it) fromJson(pose, m.pose.emplace_back());
  }
  if (const auto it = j.find("twist"); it != j.end() && it->is_array()) {
    for (const json& twist : *it) fromJson(twist, m.twist.emplace_back());
  }
}
json toJson(const gazebo_msgs::ModelStates& m) {
  json poses = json::array();
  for (const auto& pose : m.pose) poses.push_back(toJson(pose));
  json twists = json::array();
  for (const auto& twist : m.twist) twists.push_back(toJson(twist));
  return {{"name", m.name}, {"pose", std::move(poses)}, {"twist", std::move(twists)}};
}

// Declared ahead of listFrom/listOf, which find them by ordinary lookup only
// (argument-dependent lookup searches ROS's namespaces, not this one).
void fromJson(const json& j, geometry_msgs::Wrench& m);
json toJson(const geometry_msgs::Wrench& m);
void fromJson(const json& j, gazebo_msgs::ContactState& m);
json toJson(const gazebo_msgs::ContactState& m);

// A list of messages under key (missing or not a list: empty), and back.
template <class Vector>
void listFrom(const json& j, const char* key, Vector& out) {
  out.clear();
  if (const auto it = j.find(key); it != j.end() && it->is_array()) {
    for (const json& item : *it) fromJson(item, out.emplace_back());
  }
}
template <class Vector>
json listOf(const Vector& items) {
  json out = json::array();
  for (const auto& item : items) out.push_back(toJson(item));
  return out;
}

void fromJson(const json& j, geometry_msgs::Wrench& m) {
  fromJson(child(j, "force"), m.force);
  fromJson(child(j, "torque"), m.torque);
}
json toJson(const geometry_msgs::Wrench& m) { return {{"force", toJson(m.force)}, {"torque", toJson(m.torque)}}; }

void fromJson(const json& j, geometry_msgs::WrenchStamped& m) {
  m.header.stamp = stampFrom(j);
  m.header.frame_id = text(j, "frame_id");
  fromJson(child(j, "wrench"), m.wrench);
}
json toJson(const geometry_msgs::WrenchStamped& m) {
  return {{"stamp", seconds(m.header.stamp)}, {"frame_id", m.header.frame_id}, {"wrench", toJson(m.wrench)}};
}

// The covariances keep ROS's "-1 in element 0: not measured" as they are.
void fromJson(const json& j, sensor_msgs::Imu& m) {
  m.header.stamp = stampFrom(j);
  m.header.frame_id = text(j, "frame_id");
  fromJson(child(j, "orientation"), m.orientation);
  covarianceFrom(j, m.orientation_covariance, "orientation_covariance");
  fromJson(child(j, "angular_velocity"), m.angular_velocity);
  covarianceFrom(j, m.angular_velocity_covariance, "angular_velocity_covariance");
  fromJson(child(j, "linear_acceleration"), m.linear_acceleration);
  covarianceFrom(j, m.linear_acceleration_covariance, "linear_acceleration_covariance");
}
json toJson(const sensor_msgs::Imu& m) {
  return {{"stamp", seconds(m.header.stamp)},
          {"frame_id", m.header.frame_id},
          {"orientation", toJson(m.orientation)},
          {"orientation_covariance", covarianceOf(m.orientation_covariance)},
          {"angular_velocity", toJson(m.angular_velocity)},
          {"angular_velocity_covariance", covarianceOf(m.angular_velocity_covariance)},
          {"linear_acceleration", toJson(m.linear_acceleration)},
          {"linear_acceleration_covariance", covarianceOf(m.linear_acceleration_covariance)}};
}

void fromJson(const json& j, gazebo_msgs::ContactState& m) {
  m.info = text(j, "info");
  m.collision1_name = text(j, "collision1_name");
  m.collision2_name = text(j, "collision2_name");
  listFrom(j, "wrenches", m.wrenches);
  fromJson(child(j, "total_wrench"), m.total_wrench);
  listFrom(j, "contact_positions", m.contact_positions);
  listFrom(j, "contact_normals", m.contact_normals);
  m.depths = numbers(j, "depths");
}
json toJson(const gazebo_msgs::ContactState& m) {
  return {{"info", m.info},
          {"collision1_name", m.collision1_name},
          {"collision2_name", m.collision2_name},
          {"wrenches", listOf(m.wrenches)},
          {"total_wrench", toJson(m.total_wrench)},
          {"contact_positions", listOf(m.contact_positions)},
          {"contact_normals", listOf(m.contact_normals)},
          {"depths", values(m.depths)}};
}

void fromJson(const json& j, gazebo_msgs::ContactsState& m) {
  m.header.stamp = stampFrom(j);
  m.header.frame_id = text(j, "frame_id");
  listFrom(j, "states", m.states);
}
json toJson(const gazebo_msgs::ContactsState& m) {
  return {{"stamp", seconds(m.header.stamp)}, {"frame_id", m.header.frame_id}, {"states", listOf(m.states)}};
}

template <class Msg>
json serialiseAndBack(const json& msg) {
  Msg original;
  fromJson(msg, original);
  const ros::SerializedMessage bytes = ros::serialization::serializeMessage(original);
  Msg copy;
  // serializeMessage prefixes the length (4 bytes); the message follows.
  ros::serialization::IStream stream(bytes.message_start, static_cast<std::uint32_t>(bytes.num_bytes - 4));
  ros::serialization::deserialize(stream, copy);
  return toJson(copy);
}

// --- registry ---------------------------------------------------------------------
// How many messages a ROS publisher of a state topic queues for a slow
// subscriber (50 Hz or more arrive), and how many commands wait: one, as
// ros_control's controllers subscribe, so a late command never arrives behind
// newer ones.
constexpr std::uint32_t kStateQueueSize = 100;
constexpr std::uint32_t kCommandQueueSize = 1;

template <class Msg>
BridgedType bridged(bool command) {
  BridgedType type;
  type.name = ros::message_traits::DataType<Msg>::value();
  type.command = command;
  type.advertise = [](ros::NodeHandle& nh, const std::string& topic) -> JsonPublisher {
    auto publisher = std::make_shared<ros::Publisher>(nh.advertise<Msg>(topic, kStateQueueSize));
    return [publisher](const json& msg) {
      Msg ros_msg;
      fromJson(msg, ros_msg);
      publisher->publish(ros_msg);
    };
  };
  type.subscribe = [](ros::NodeHandle& nh, const std::string& topic, JsonCallback callback) {
    // roscpp does not catch what a subscriber callback throws: nothing may.
    return nh.subscribe<Msg>(topic, kCommandQueueSize, [callback = std::move(callback), topic](const typename Msg::ConstPtr& msg) {
      try {
        callback(toJson(*msg));
      } catch (const std::exception& e) {
        ROS_ERROR("servoloop bridge: %s: %s", topic.c_str(), e.what());
      }
    });
  };
  type.round_trip = [](const json& msg) { return serialiseAndBack<Msg>(msg); };
  return type;
}

const std::map<std::string, BridgedType, std::less<>>& registry() {
  static const std::map<std::string, BridgedType, std::less<>> types = [] {
    std::map<std::string, BridgedType, std::less<>> out;
    for (BridgedType type : {bridged<std_msgs::Float64>(true), bridged<std_msgs::Float64MultiArray>(true),
                             bridged<std_msgs::Bool>(true), bridged<geometry_msgs::Twist>(true),
                             bridged<trajectory_msgs::JointTrajectory>(true), bridged<sensor_msgs::JointState>(false),
                             bridged<control_msgs::JointControllerState>(false),
                             bridged<control_msgs::JointTrajectoryControllerState>(false),
                             bridged<nav_msgs::Odometry>(false), bridged<tf2_msgs::TFMessage>(false),
                             bridged<diagnostic_msgs::DiagnosticArray>(false),
                             bridged<gazebo_msgs::ModelStates>(false),
                             bridged<geometry_msgs::WrenchStamped>(false), bridged<sensor_msgs::Imu>(false),
                             bridged<gazebo_msgs::ContactsState>(false)}) {
      out.emplace(type.name, std::move(type));
    }
    return out;
  }();
  return types;
}

}  // namespace

void fromJson(const json& j, control_msgs::JointTrajectoryControllerState& m) {
  m.header.stamp = stampFrom(j);
  m.joint_names = strings(j, "joint_names");
  fromJson(child(j, "desired"), m.desired);
  fromJson(child(j, "actual"), m.actual);
  fromJson(child(j, "error"), m.error);
}
json toJson(const control_msgs::JointTrajectoryControllerState& m) {
  return {{"stamp", seconds(m.header.stamp)}, {"joint_names", m.joint_names}, {"desired", toJson(m.desired)},
          {"actual", toJson(m.actual)}, {"error", toJson(m.error)}};
}

void fromJson(const json& j, nav_msgs::Odometry& m) {
  m.header.stamp = stampFrom(j);
  m.header.frame_id = text(j, "frame_id");
  m.child_frame_id = text(j, "child_frame_id");
  const json& pose = child(j, "pose");
  fromJson(child(pose, "position"), m.pose.pose.position);
  fromJson(child(pose, "orientation"), m.pose.pose.orientation);
  covarianceFrom(pose, m.pose.covariance);
  const json& twist = child(j, "twist");
  fromJson(child(twist, "linear"), m.twist.twist.linear);
  fromJson(child(twist, "angular"), m.twist.twist.angular);
  covarianceFrom(twist, m.twist.covariance);
}
json toJson(const nav_msgs::Odometry& m) {
  return {{"stamp", seconds(m.header.stamp)},
          {"frame_id", m.header.frame_id},
          {"child_frame_id", m.child_frame_id},
          {"pose", {{"position", toJson(m.pose.pose.position)}, {"orientation", toJson(m.pose.pose.orientation)},
                    {"covariance", covarianceOf(m.pose.covariance)}}},
          {"twist", {{"linear", toJson(m.twist.twist.linear)}, {"angular", toJson(m.twist.twist.angular)},
                     {"covariance", covarianceOf(m.twist.covariance)}}}};
}

void fromJson(const json& j, geometry_msgs::Pose& m) {
  fromJson(child(j, "position"), m.position);
  fromJson(child(j, "orientation"), m.orientation);
}
json toJson(const geometry_msgs::Pose& m) {
  return {{"position", toJson(m.position)}, {"orientation", toJson(m.orientation)}};
}

void fromJson(const json& j, geometry_msgs::Twist& m) {
  fromJson(child(j, "linear"), m.linear);
  fromJson(child(j, "angular"), m.angular);
}
json toJson(const geometry_msgs::Twist& m) { return {{"linear", toJson(m.linear)}, {"angular", toJson(m.angular)}}; }

void fromJson(const json& j, trajectory_msgs::JointTrajectoryPoint& m) {
  m.positions = numbers(j, "positions");
  m.velocities = numbers(j, "velocities");
  m.accelerations = numbers(j, "accelerations");
  m.effort = numbers(j, "effort");
  const double t = number(j, "time_from_start");
  m.time_from_start = ros::Duration(std::isfinite(t) ? t : 0.0);
}
json toJson(const trajectory_msgs::JointTrajectoryPoint& m) {
  return {{"positions", values(m.positions)}, {"velocities", values(m.velocities)},
          {"accelerations", values(m.accelerations)}, {"effort", values(m.effort)},
          {"time_from_start", seconds(m.time_from_start)}};
}

void fromJson(const json& j, trajectory_msgs::JointTrajectory& m) {
  m.header.stamp = stampFrom(j);
  m.joint_names = strings(j, "joint_names");
  m.points.clear();
  if (const auto it = j.find("points"); it != j.end() && it->is_array()) {
    for (const json& point : *it) fromJson(point, m.points.emplace_back());
  }
}
json toJson(const trajectory_msgs::JointTrajectory& m) {
  json points = json::array();
  for (const auto& point : m.points) points.push_back(toJson(point));
  return {{"stamp", seconds(m.header.stamp)}, {"joint_names", m.joint_names}, {"points", std::move(points)}};
}

const BridgedType* findBridgedType(std::string_view type_name) {
  const auto& types = registry();
  const auto it = types.find(type_name);
  return it == types.end() ? nullptr : &it->second;
}

std::vector<std::string> bridgedTypeNames() {
  std::vector<std::string> names;
  for (const auto& [name, type] : registry()) names.push_back(name);
  return names;
}

json roundTrip(std::string_view type_name, const json& msg) {
  const BridgedType* type = findBridgedType(type_name);
  if (type == nullptr) throw std::invalid_argument("the ROS 1 bridge does not carry message type '" + std::string(type_name) + "'");
  return type->round_trip(msg);
}

}  // namespace servoloop::ros1
