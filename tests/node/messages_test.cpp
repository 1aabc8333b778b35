// Message conversions: JSON both ways, rostopic-style text, CSV columns, and
// errors that name the field at fault. Expected strings are written by hand.
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "thrown_message.hpp"
#include "servoloop/node/message_json.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::node {
namespace {

using servoloop::testing::thrownMessage;

using nlohmann::json;
using ::testing::HasSubstr;

sensor_msgs::JointState threeJoints() {
  sensor_msgs::JointState msg;
  msg.stamp = 0.5;
  msg.name = {"j1", "j2", "j3"};
  msg.position = {0.1, -0.2, 3.0};
  msg.velocity = {1.0, 0.0, -1.5};
  msg.effort = {10.0, 20.0, 30.0};
  return msg;
}

// Found by fuzzing: text of a message holding a string that is not UTF-8
// (YAML lets one through) threw from the JSON library.
TEST(Messages, TextOfStringsThatAreNotUtf8DoesNotThrow) {
  const nlohmann::json message = parseMessageText("[1, 2, \"3\xF9\"]", "test");
  std::string text;
  EXPECT_NO_THROW(text = messageToText("std_msgs/Float64MultiArray", {{"data", message}}));
  EXPECT_NE(text.find("\xEF\xBF\xBD"), std::string::npos) << "the bad byte shows as U+FFFD: " << text;
}

TEST(Messages, TypeNames) {
  EXPECT_EQ(std_msgs::Float64::kTypeName, "std_msgs/Float64");
  EXPECT_EQ(std_msgs::Float64MultiArray::kTypeName, "std_msgs/Float64MultiArray");
  EXPECT_EQ(sensor_msgs::JointState::kTypeName, "sensor_msgs/JointState");
  EXPECT_EQ(control_msgs::JointControllerState::kTypeName, "control_msgs/JointControllerState");
  EXPECT_EQ(trajectory_msgs::JointTrajectory::kTypeName, "trajectory_msgs/JointTrajectory");
  EXPECT_EQ(control_msgs::JointTrajectoryControllerState::kTypeName, "control_msgs/JointTrajectoryControllerState");
  EXPECT_EQ(geometry_msgs::WrenchStamped::kTypeName, "geometry_msgs/WrenchStamped");
  EXPECT_EQ(sensor_msgs::Imu::kTypeName, "sensor_msgs/Imu");
  EXPECT_EQ(gazebo_msgs::ContactsState::kTypeName, "gazebo_msgs/ContactsState");
  EXPECT_EQ(knownMessageTypes(),
            (std::vector<std::string>{"control_msgs/JointControllerState",
                                      "control_msgs/JointTrajectoryControllerState", "diagnostic_msgs/DiagnosticArray",
                                      "gazebo_msgs/ContactsState", "gazebo_msgs/ModelStates", "geometry_msgs/Twist",
                                      "geometry_msgs/WrenchStamped", "nav_msgs/Odometry", "sensor_msgs/Imu",
                                      "sensor_msgs/JointState", "std_msgs/Bool", "std_msgs/Float64",
                                      "std_msgs/Float64MultiArray", "tf2_msgs/TFMessage",
                                      "trajectory_msgs/JointTrajectory"}));
  EXPECT_TRUE(isKnownMessageType("std_msgs/Float64"));
  EXPECT_FALSE(isKnownMessageType("std_msgs/Float32"));
}

// gazebo_msgs/ModelStates as `topic echo` shows it and `topic pub` reads it:
// one pose and one twist per name.
TEST(Messages, ModelStatesJsonRoundTripAndOnePoseAndTwistPerName) {
  gazebo_msgs::ModelStates msg;
  msg.name = {"ground_plane", "crate"};
  msg.pose.resize(2);
  msg.twist.resize(2);
  msg.pose[1].position = {1.0, -2.0, 0.1};
  msg.pose[1].orientation = {0.0, 0.0, 0.6, 0.8};
  msg.twist[1].linear = {0.5, 0.0, 0.0};
  msg.twist[1].angular = {0.0, 0.0, -1.0};
  const json j = toJson(msg);
  EXPECT_EQ(j["pose"][1]["orientation"]["z"], 0.6);
  EXPECT_EQ(j["twist"][1]["angular"]["z"], -1.0);
  gazebo_msgs::ModelStates back;
  fromJson(j, back);
  EXPECT_EQ(back.name, msg.name);
  EXPECT_EQ(back.pose[1].position.y, -2.0);
  EXPECT_EQ(back.pose[1].orientation.w, 0.8);
  EXPECT_EQ(back.pose[0].orientation.w, 1.0);
  EXPECT_EQ(back.twist[1].linear.x, 0.5);
  json ragged = j;
  ragged["twist"].erase(1);
  try {
    fromJson(ragged, back);
    ADD_FAILURE() << "two names with one twist were accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("2 names, 2 poses and 1 twists"), std::string::npos) << e.what();
  }
}

// geometry_msgs/WrenchStamped with ROS's field names, header flattened into
// stamp and frame_id as for the other stamped types.
TEST(Messages, WrenchStampedJsonRoundTripTextAndCsv) {
  geometry_msgs::WrenchStamped msg;
  msg.stamp = 0.25;
  msg.frame_id = "wrist_ft";
  msg.wrench.force = {1.5, -2.0, 9.81};
  msg.wrench.torque = {0.0, 0.125, -0.5};
  const json j = toJson(msg);
  EXPECT_EQ(j, json::parse(R"({"stamp": 0.25, "frame_id": "wrist_ft",
                               "wrench": {"force": {"x": 1.5, "y": -2.0, "z": 9.81},
                                          "torque": {"x": 0.0, "y": 0.125, "z": -0.5}}})"));
  const auto back = messageFromJson<geometry_msgs::WrenchStamped>(json::parse(j.dump()));
  EXPECT_EQ(back.stamp, 0.25);
  EXPECT_EQ(back.frame_id, "wrist_ft");
  EXPECT_EQ(back.wrench.force.z, 9.81);
  EXPECT_EQ(back.wrench.torque.y, 0.125);
  EXPECT_EQ(toJson(back), j);

  // As a user writes it for `topic pub`: fields left out stay zero.
  const auto typed = messageFromJson<geometry_msgs::WrenchStamped>(parseMessageText("{wrench: {force: {z: 2}}}"));
  EXPECT_EQ(typed.wrench.force.z, 2.0);
  EXPECT_EQ(typed.wrench.torque.x, 0.0);
  EXPECT_EQ(typed.frame_id, "");

  EXPECT_EQ(toText(msg),
            "stamp: 0.25\nframe_id: \"wrist_ft\"\nwrench:\n"
            "  force:\n    x: 1.5\n    y: -2.0\n    z: 9.81\n"
            "  torque:\n    x: 0.0\n    y: 0.125\n    z: -0.5\n");
  EXPECT_EQ(csvHeader(msg), "time,frame_id,wrench.force.x,wrench.force.y,wrench.force.z,wrench.torque.x,"
                            "wrench.torque.y,wrench.torque.z");
  EXPECT_EQ(csvRow(msg, Time(0.25)), "0.25,wrist_ft,1.5,-2.0,9.81,0.0,0.125,-0.5");

  EXPECT_EQ(thrownMessage([] {
              messageFromJson<geometry_msgs::WrenchStamped>(json::parse(R"({"wrench": {"force": {"q": 1}}})"));
            }),
            "geometry_msgs/WrenchStamped: field 'wrench.force.q': expected one of the fields of force, got 1");
  EXPECT_EQ(thrownMessage([] { messageFromJson<geometry_msgs::WrenchStamped>(json::parse(R"({"wrench": 3})")); }),
            "geometry_msgs/WrenchStamped: field 'wrench': expected an object with fields force, torque, got 3");
  EXPECT_EQ(thrownMessage([] { messageFromJson<geometry_msgs::WrenchStamped>(json::parse(R"({"force": {}})")); }),
            "geometry_msgs/WrenchStamped: unknown field 'force'; the fields are: stamp, frame_id, wrench");
}

// sensor_msgs/Imu: three values with their 3×3 covariances; -1 in a
// covariance's first element ("not measured") survives, as does NaN.
TEST(Messages, ImuJsonRoundTripAndCovarianceSizes) {
  sensor_msgs::Imu msg;
  msg.stamp = 1.5;
  msg.frame_id = "imu_link";
  msg.orientation = {0.0, 0.0, 0.6, 0.8};
  msg.orientation_covariance[0] = -1.0;
  msg.angular_velocity = {0.1, -0.2, 0.3};
  msg.angular_velocity_covariance = {1e-4, 0, 0, 0, 1e-4, 0, 0, 0, 1e-4};
  msg.linear_acceleration = {0.0, 0.0, 9.81};
  msg.linear_acceleration_covariance[8] = std::numeric_limits<double>::quiet_NaN();
  const json j = toJson(msg);
  EXPECT_EQ(j["frame_id"], "imu_link");
  EXPECT_EQ(j["orientation"], json::parse(R"({"x": 0.0, "y": 0.0, "z": 0.6, "w": 0.8})"));
  EXPECT_EQ(j["orientation_covariance"], json::parse("[-1.0, 0, 0, 0, 0, 0, 0, 0, 0]"));
  EXPECT_EQ(j["angular_velocity"], json::parse(R"({"x": 0.1, "y": -0.2, "z": 0.3})"));
  EXPECT_EQ(j["angular_velocity_covariance"][4], 1e-4);
  EXPECT_EQ(j["linear_acceleration"]["z"], 9.81);
  EXPECT_EQ(j.size(), 8u);
  const auto back = messageFromJson<sensor_msgs::Imu>(json::parse(j.dump()));  // NaN travels as null
  EXPECT_EQ(back.stamp, 1.5);
  EXPECT_EQ(back.frame_id, "imu_link");
  EXPECT_EQ(back.orientation.w, 0.8);
  EXPECT_EQ(back.orientation_covariance[0], -1.0);
  EXPECT_EQ(back.angular_velocity.y, -0.2);
  EXPECT_EQ(back.angular_velocity_covariance, msg.angular_velocity_covariance);
  EXPECT_EQ(back.linear_acceleration.z, 9.81);
  EXPECT_TRUE(std::isnan(back.linear_acceleration_covariance[8]));
  // A left-out orientation is the identity.
  EXPECT_EQ(messageFromJson<sensor_msgs::Imu>(json::object()).orientation.w, 1.0);

  EXPECT_EQ(thrownMessage([] {
              messageFromJson<sensor_msgs::Imu>(json::parse(R"({"angular_velocity_covariance": [1, 2, 3]})"));
            }),
            "sensor_msgs/Imu: field 'angular_velocity_covariance': expected a list of 9 numbers, got a list");
  EXPECT_EQ(thrownMessage([] { messageFromJson<sensor_msgs::Imu>(json::parse(R"({"orientation": {"x": "a"}})")); }),
            "sensor_msgs/Imu: field 'orientation.x': expected a number, got string \"a\"");
  EXPECT_THAT(thrownMessage([] { messageFromJson<sensor_msgs::Imu>(json::parse(R"({"header": {}})")); }),
              HasSubstr("unknown field 'header'; the fields are: stamp, frame_id, orientation"));
}

// gazebo_msgs/ContactsState as gazebo_ros_bumper publishes it: per contact
// point a wrench, a position, a normal and a depth.
TEST(Messages, ContactsStateJsonRoundTripAndOneOfEachPerContactPoint) {
  gazebo_msgs::ContactsState msg;
  msg.stamp = 3.0;
  msg.frame_id = "world";
  msg.states.resize(2);
  msg.states[1].collision1_name = "box::link::collision";  // a state with no points
  gazebo_msgs::ContactState& c = msg.states[0];
  c.info = "Debug:  i:(0/1)     my geom:box::link::collision   other geom:ground_plane::link::collision";
  c.collision1_name = "box::link::collision";
  c.collision2_name = "ground_plane::link::collision";
  c.wrenches.resize(2);
  c.wrenches[0].force = {0.0, 0.0, 4.9};
  c.wrenches[1].force = {0.0, 0.0, 4.9};
  c.wrenches[1].torque = {0.1, 0.0, 0.0};
  c.total_wrench.force = {0.0, 0.0, 9.8};
  c.total_wrench.torque = {0.1, 0.0, 0.0};
  c.contact_positions = {{0.05, 0.05, 0.0}, {-0.05, -0.05, 0.0}};
  c.contact_normals = {{0.0, 0.0, 1.0}, {0.0, 0.0, 1.0}};
  c.depths = {1e-4, 2e-4};
  const json j = toJson(msg);
  EXPECT_EQ(j["stamp"], 3.0);
  EXPECT_EQ(j["frame_id"], "world");
  ASSERT_EQ(j["states"].size(), 2u);
  const json& state = j["states"][0];
  EXPECT_EQ(state["collision2_name"], "ground_plane::link::collision");
  EXPECT_EQ(state["wrenches"][1]["torque"], json::parse(R"({"x": 0.1, "y": 0.0, "z": 0.0})"));
  EXPECT_EQ(state["total_wrench"]["force"]["z"], 9.8);
  EXPECT_EQ(state["contact_positions"][1], json::parse(R"({"x": -0.05, "y": -0.05, "z": 0.0})"));
  EXPECT_EQ(state["contact_normals"][0]["z"], 1.0);
  EXPECT_EQ(state["depths"], json::parse("[1e-4, 2e-4]"));
  EXPECT_EQ(state.size(), 8u);

  const auto back = messageFromJson<gazebo_msgs::ContactsState>(json::parse(j.dump()));
  EXPECT_EQ(back.stamp, 3.0);
  ASSERT_EQ(back.states.size(), 2u);
  EXPECT_EQ(back.states[0].info, c.info);
  EXPECT_EQ(back.states[0].collision1_name, c.collision1_name);
  ASSERT_EQ(back.states[0].wrenches.size(), 2u);
  EXPECT_EQ(back.states[0].wrenches[1].torque.x, 0.1);
  EXPECT_EQ(back.states[0].total_wrench.force.z, 9.8);
  EXPECT_EQ(back.states[0].contact_positions[1].x, -0.05);
  EXPECT_EQ(back.states[0].contact_normals[1].z, 1.0);
  EXPECT_EQ(back.states[0].depths, c.depths);
  EXPECT_TRUE(back.states[1].wrenches.empty());
  EXPECT_EQ(toJson(back), j);

  json ragged = j;
  ragged["states"][0]["depths"].erase(1);
  EXPECT_EQ(thrownMessage([&] { messageFromJson<gazebo_msgs::ContactsState>(ragged); }),
            "gazebo_msgs/ContactsState: states[0]: 2 wrenches, 2 contact_positions, 2 contact_normals and 1 depths; "
            "give one of each per contact point");
  json bad = j;
  bad["states"][0]["wrenches"][1]["force"]["z"] = "heavy";
  EXPECT_EQ(thrownMessage([&] { messageFromJson<gazebo_msgs::ContactsState>(bad); }),
            "gazebo_msgs/ContactsState: field 'states[0].wrenches[1].force.z': expected a number, got string "
            "\"heavy\"");
  bad = j;
  bad["states"][0]["contact_normals"][0] = 1.0;
  EXPECT_EQ(thrownMessage([&] { messageFromJson<gazebo_msgs::ContactsState>(bad); }),
            "gazebo_msgs/ContactsState: field 'states[0].contact_normals[0]': expected an object, got 1.0");
  bad = j;
  bad["states"][1]["position"] = json::array();
  EXPECT_THAT(thrownMessage([&] { messageFromJson<gazebo_msgs::ContactsState>(bad); }),
              HasSubstr("unknown field 'states[1].position'; the fields are: info, collision1_name"));
}

// `topic pub` creates a topic of each new type and `topic echo` reads it back.
TEST(Messages, SensorTypesTravelTheBusAsJson) {
  realtime::TopicBus bus;
  std::map<std::string, json> received;  // type → message
  std::vector<realtime::Subscription> subscriptions;
  const json wrench = json::parse(R"({"stamp": 0.5, "frame_id": "ft", "wrench": {"force": {"x": 1.0, "y": 2.0,
      "z": 3.0}, "torque": {"x": 0.0, "y": 0.0, "z": -1.0}}})");
  const json imu = toJson(sensor_msgs::Imu{});
  const json contacts = json::parse(R"({"stamp": 0.0, "frame_id": "world", "states": []})");
  const std::pair<const char*, const json*> cases[] = {
      {"geometry_msgs/WrenchStamped", &wrench}, {"sensor_msgs/Imu", &imu}, {"gazebo_msgs/ContactsState", &contacts}};
  for (const auto& entry : cases) {
    const std::string type = entry.first;
    const std::string topic = "/robot/" + type;
    subscriptions.push_back(
        subscribeJson(bus, topic, [&received, type](Time, const json& m) { received[type] = m; }));
    publishJson(bus, topic, *entry.second, type);
    EXPECT_EQ(bus.typeOf(topic), type);
  }
  bus.flush();
  ASSERT_EQ(received.size(), 3u);
  for (const auto& entry : cases) {
    const auto it = received.find(entry.first);
    ASSERT_NE(it, received.end()) << entry.first;
    EXPECT_EQ(it->second, *entry.second) << entry.first;
  }
  EXPECT_EQ(normalizeMessage("geometry_msgs/WrenchStamped", json::object())["wrench"]["torque"]["z"], 0.0);
}

TEST(Messages, Float64JsonRoundTrip) {
  EXPECT_EQ(toJson(std_msgs::Float64{1.5}), json::parse(R"({"data": 1.5})"));
  EXPECT_EQ(messageFromJson<std_msgs::Float64>(json::parse(R"({"data": -0.25})")).data, -0.25);
  // Integers are accepted for doubles; the bare value works for one-field messages.
  EXPECT_EQ(messageFromJson<std_msgs::Float64>(json::parse(R"({"data": 2})")).data, 2.0);
  EXPECT_EQ(messageFromJson<std_msgs::Float64>(json(3.5)).data, 3.5);
  EXPECT_EQ(messageFromJson<std_msgs::Float64>(json::object()).data, 0.0);
}

TEST(Messages, BoolJson) {
  EXPECT_EQ(std_msgs::Bool::kTypeName, "std_msgs/Bool");
  EXPECT_EQ(toJson(std_msgs::Bool{true}), json::parse(R"({"data": true})"));
  EXPECT_TRUE(messageFromJson<std_msgs::Bool>(json::parse(R"({"data": true})")).data);
  EXPECT_TRUE(messageFromJson<std_msgs::Bool>(json(true)).data);  // `topic pub /estop std_msgs/Bool true`
  EXPECT_FALSE(messageFromJson<std_msgs::Bool>(json::object()).data);
  // A number is not a switch: ROS's Bool takes true or false only.
  EXPECT_THROW(messageFromJson<std_msgs::Bool>(json::parse(R"({"data": 1})")), Error);
  EXPECT_THROW(messageFromJson<std_msgs::Bool>(json::parse(R"({"on": true})")), Error);
}

TEST(Messages, DiagnosticArrayJsonRoundTripAndErrors) {
  diagnostic_msgs::DiagnosticArray msg;
  msg.stamp = 2.5;
  msg.status.push_back({diagnostic_msgs::DiagnosticStatus::kWarn, "/arm: control loop", "overran", "mock",
                        {{"cycles", "2000"}, {"overruns", "3"}}});
  const json j = toJson(msg);
  EXPECT_EQ(j.dump(), R"({"stamp":2.5,"status":[{"hardware_id":"mock","level":1,"message":"overran",)"
                      R"("name":"/arm: control loop","values":[{"key":"cycles","value":"2000"},)"
                      R"({"key":"overruns","value":"3"}]}]})");
  const auto back = messageFromJson<diagnostic_msgs::DiagnosticArray>(j);
  ASSERT_EQ(back.status.size(), 1u);
  EXPECT_EQ(back.status[0].level, 1);
  EXPECT_EQ(back.status[0].values[1].value, "3");
  try {
    messageFromJson<diagnostic_msgs::DiagnosticArray>(json::parse(R"({"status": [{"level": 7}]})"));
    ADD_FAILURE() << "level 7 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("status[0]"), std::string::npos) << e.what();
  }
}

TEST(Messages, Float64MultiArrayJsonRoundTrip) {
  const std_msgs::Float64MultiArray msg{{1.0, -2.5, 1e-9}};
  EXPECT_EQ(toJson(msg).dump(), R"({"data":[1.0,-2.5,1e-09]})");
  EXPECT_EQ(messageFromJson<std_msgs::Float64MultiArray>(toJson(msg)).data, msg.data);
  EXPECT_EQ(messageFromJson<std_msgs::Float64MultiArray>(json::parse("[1, 2]")).data,
            (std::vector<double>{1.0, 2.0}));
  // ROS's layout field is accepted and ignored.
  EXPECT_EQ(messageFromJson<std_msgs::Float64MultiArray>(
                json::parse(R"({"layout": {"dim": [], "data_offset": 0}, "data": [4]})"))
                .data,
            (std::vector<double>{4.0}));
}

TEST(Messages, JointStateJsonRoundTrip) {
  const sensor_msgs::JointState msg = threeJoints();
  EXPECT_EQ(toJson(msg), json::parse(R"({"stamp": 0.5, "name": ["j1", "j2", "j3"],
                                         "position": [0.1, -0.2, 3.0], "velocity": [1.0, 0.0, -1.5],
                                         "effort": [10.0, 20.0, 30.0]})"));
  const auto back = messageFromJson<sensor_msgs::JointState>(json::parse(toJson(msg).dump()));
  EXPECT_EQ(back.stamp, msg.stamp);
  EXPECT_EQ(back.name, msg.name);
  EXPECT_EQ(back.position, msg.position);
  EXPECT_EQ(back.velocity, msg.velocity);
  EXPECT_EQ(back.effort, msg.effort);
}

TEST(Messages, JointControllerStateJsonRoundTrip) {
  control_msgs::JointControllerState msg;
  msg.stamp = 1.25;
  msg.set_point = 0.5;
  msg.process_value = 0.4;
  msg.process_value_dot = -0.1;
  msg.error = 0.1;
  msg.time_step = 0.01;
  msg.command = 2.0;
  msg.p = 10.0;
  msg.i = 1.0;
  msg.d = 0.5;
  msg.i_clamp = 3.0;
  msg.antiwindup = true;
  const json expected = json::parse(R"({"stamp": 1.25, "set_point": 0.5, "process_value": 0.4,
      "process_value_dot": -0.1, "error": 0.1, "time_step": 0.01, "command": 2.0, "p": 10.0, "i": 1.0,
      "d": 0.5, "i_clamp": 3.0, "antiwindup": true})");
  EXPECT_EQ(toJson(msg), expected);
  const auto back = messageFromJson<control_msgs::JointControllerState>(json::parse(expected.dump()));
  EXPECT_EQ(toJson(back), expected);
}

TEST(Messages, JointTrajectoryJsonRoundTripAndErrors) {
  // As a user writes it for `topic pub`: YAML, integers for numbers, fields left out.
  const auto msg = messageFromJson<trajectory_msgs::JointTrajectory>(parseMessageText(
      "{joint_names: [a, b], points: [{positions: [1, 2], time_from_start: 0.5}, "
      "{positions: [3, 4], velocities: [0, 0], time_from_start: 1}]}"));
  EXPECT_EQ(msg.stamp, 0.0);
  ASSERT_EQ(msg.points.size(), 2u);
  EXPECT_EQ(msg.points[0].positions, (std::vector<double>{1.0, 2.0}));
  EXPECT_TRUE(msg.points[0].velocities.empty());
  EXPECT_EQ(msg.points[1].velocities, (std::vector<double>{0.0, 0.0}));
  EXPECT_DOUBLE_EQ(msg.points[1].time_from_start, 1.0);
  const auto again = messageFromJson<trajectory_msgs::JointTrajectory>(toJson(msg));
  EXPECT_EQ(again.joint_names, msg.joint_names);
  EXPECT_EQ(again.points[1].positions, msg.points[1].positions);

  EXPECT_EQ(thrownMessage([] {
              messageFromJson<trajectory_msgs::JointTrajectory>(
                  json::parse(R"({"points": [{"positions": [1]}, {"positions": ["x"]}]})"));
            }),
            "trajectory_msgs/JointTrajectory: field 'points[1].positions[0]': expected a number, got string \"x\"");
  EXPECT_EQ(thrownMessage([] {
              messageFromJson<trajectory_msgs::JointTrajectory>(json::parse(R"({"points": [{"position": [1]}]})"));
            }),
            "trajectory_msgs/JointTrajectory: unknown field 'points[0].position'; the fields are: positions, "
            "velocities, accelerations, effort, time_from_start");
  EXPECT_THAT(thrownMessage([] { messageFromJson<trajectory_msgs::JointTrajectory>(json::parse(R"({"points": [3]})")); }),
              HasSubstr("field 'points[0]': expected an object with fields positions"));
  // A command must be finite, wherever the NaN hides.
  EXPECT_EQ(thrownMessage([] {
              requireFiniteCommand("trajectory_msgs/JointTrajectory",
                                   json::parse(R"({"points": [{"positions": [1, null]}]})"));
            }),
            "trajectory_msgs/JointTrajectory: points[0].positions[1] is nan; a trajectory must hold finite numbers");
}

TEST(Messages, JointTrajectoryControllerStateTextAndCsv) {
  control_msgs::JointTrajectoryControllerState state;
  state.stamp = 1.5;
  state.joint_names = {"a"};
  state.desired.positions = {0.5};
  state.actual.positions = {0.25};
  state.error.positions = {0.25};
  EXPECT_EQ(csvHeader(state),
            "time,joint_names[0],desired.positions[0],desired.time_from_start,actual.positions[0],"
            "actual.time_from_start,error.positions[0],error.time_from_start");
  EXPECT_EQ(csvRow(state, Time(1.5)), "1.5,a,0.5,0.0,0.25,0.0,0.25,0.0");
  // Nested points print their fields in ROS order, as `rostopic echo` does.
  EXPECT_EQ(toText(state),
            "stamp: 1.5\njoint_names: [a]\n"
            "desired:\n  positions: [0.5]\n  velocities: []\n  accelerations: []\n  effort: []\n  time_from_start: 0.0\n"
            "actual:\n  positions: [0.25]\n  velocities: []\n  accelerations: []\n  effort: []\n  time_from_start: 0.0\n"
            "error:\n  positions: [0.25]\n  velocities: []\n  accelerations: []\n  effort: []\n  time_from_start: 0.0\n");
  const auto again = messageFromJson<control_msgs::JointTrajectoryControllerState>(toJson(state));
  EXPECT_EQ(again.desired.positions, state.desired.positions);
  EXPECT_EQ(again.joint_names, state.joint_names);
}

TEST(Messages, TwistTfAndOdometryCovariance) {
  // `rostopic pub cmd_vel geometry_msgs/Twist` as ROS users write it.
  const auto twist = messageFromJson<geometry_msgs::Twist>(parseMessageText("{linear: {x: 0.5}, angular: {z: -1}}"));
  EXPECT_EQ(twist.linear.x, 0.5);
  EXPECT_EQ(twist.angular.z, -1.0);
  EXPECT_EQ(twist.linear.y, 0.0);
  EXPECT_EQ(thrownMessage([] { requireFiniteCommand("geometry_msgs/Twist", json::parse(R"({"angular": {"z": null}})")); }),
            "geometry_msgs/Twist: angular.z is nan; a command must be a finite number");
  EXPECT_THAT(thrownMessage([] { messageFromJson<geometry_msgs::Twist>(json::parse(R"({"linear": {"w": 1}})")); }),
              HasSubstr("linear.w"));

  tf2_msgs::TFMessage tf;
  tf.transforms.resize(1);
  tf.transforms[0].frame_id = "odom";
  tf.transforms[0].child_frame_id = "base_link";
  tf.transforms[0].translation.x = 1.5;
  const auto tf_again = messageFromJson<tf2_msgs::TFMessage>(toJson(tf));
  ASSERT_EQ(tf_again.transforms.size(), 1u);
  EXPECT_EQ(tf_again.transforms[0].child_frame_id, "base_link");
  EXPECT_EQ(tf_again.transforms[0].translation.x, 1.5);
  EXPECT_EQ(tf_again.transforms[0].rotation.w, 1.0);

  nav_msgs::Odometry odom;
  odom.pose_covariance[0] = 0.25;
  odom.twist_covariance[35] = 0.5;
  const json odom_json = toJson(odom);
  ASSERT_EQ(odom_json["pose"]["covariance"].size(), 36u);
  const auto odom_again = messageFromJson<nav_msgs::Odometry>(odom_json);
  EXPECT_EQ(odom_again.pose_covariance[0], 0.25);
  EXPECT_EQ(odom_again.twist_covariance[35], 0.5);
  EXPECT_THAT(thrownMessage([] { messageFromJson<nav_msgs::Odometry>(json::parse(R"({"pose": {"covariance": [1, 2]}})")); }),
              HasSubstr("pose.covariance': expected a list of 36 numbers"));
}

TEST(Messages, NanSurvivesJsonTextAsNull) {
  const std_msgs::Float64 nan_msg{std::numeric_limits<double>::quiet_NaN()};
  const std::string text = toJson(nan_msg).dump();
  EXPECT_EQ(text, R"({"data":null})");
  EXPECT_TRUE(std::isnan(messageFromJson<std_msgs::Float64>(json::parse(text)).data));
}

TEST(Messages, MalformedJsonNamesTheField) {
  EXPECT_EQ(thrownMessage([] { messageFromJson<std_msgs::Float64>(json::parse(R"({"data": "abc"})")); }),
            "std_msgs/Float64: field 'data': expected a number, got string \"abc\"");
  EXPECT_EQ(thrownMessage([] { messageFromJson<std_msgs::Float64>(json::parse(R"({"dta": 1.0})")); }),
            "std_msgs/Float64: unknown field 'dta'; the fields are: data");
  EXPECT_THAT(thrownMessage([] { messageFromJson<std_msgs::Float64>(json::parse(R"("one")")); }),
              HasSubstr("std_msgs/Float64: expected an object with fields data, got string \"one\""));
  EXPECT_EQ(thrownMessage([] {
              messageFromJson<sensor_msgs::JointState>(
                  json::parse(R"({"name": ["a", "b"], "position": [1.0, "x"]})"));
            }),
            "sensor_msgs/JointState: field 'position[1]': expected a number, got string \"x\"");
  EXPECT_EQ(thrownMessage([] { messageFromJson<sensor_msgs::JointState>(json::parse(R"({"name": ["a", 2]})")); }),
            "sensor_msgs/JointState: field 'name[1]': expected a string, got 2");
  EXPECT_THAT(thrownMessage([] {
                messageFromJson<sensor_msgs::JointState>(
                    json::parse(R"({"name": ["a", "b", "c"], "position": [1.0, 2.0]})"));
              }),
              HasSubstr("field 'position' has 2 entries but 'name' has 3"));
  EXPECT_EQ(thrownMessage([] {
              messageFromJson<control_msgs::JointControllerState>(json::parse(R"({"antiwindup": "yes"})"));
            }),
            "control_msgs/JointControllerState: field 'antiwindup': expected true or false, got string \"yes\"");
  EXPECT_EQ(thrownMessage([] { messageFromJson<std_msgs::Float64MultiArray>(json::parse(R"({"data": 1.0})")); }),
            "std_msgs/Float64MultiArray: field 'data': expected a list of numbers, got 1.0");
}

TEST(Messages, YamlTextParsesLikeRostopicPub) {
  EXPECT_EQ(parseMessageText("data: 1.0"), json::parse(R"({"data": 1.0})"));
  EXPECT_EQ(parseMessageText("{data: 2}"), json::parse(R"({"data": 2})"));
  EXPECT_EQ(parseMessageText(R"({"data": [1, 2.5]})"), json::parse(R"({"data": [1, 2.5]})"));
  EXPECT_EQ(parseMessageText("1.0"), json(1.0));
  EXPECT_EQ(parseMessageText(""), json::object());
  EXPECT_EQ(parseMessageText("{name: [j1], flag: true, label: \"7\"}"),
            json::parse(R"({"name": ["j1"], "flag": true, "label": "7"})"));
  EXPECT_EQ(messageFromJson<std_msgs::Float64>(parseMessageText("data: 3")).data, 3.0);
  const std::string error = thrownMessage([] { parseMessageText("data: [1,", "topic pub"); });
  EXPECT_THAT(error, HasSubstr("topic pub: cannot read 'data: [1,'"));
  EXPECT_THAT(error, HasSubstr("line 1"));
}

TEST(Messages, TextFormReadsLikeRostopicEcho) {
  EXPECT_EQ(toText(std_msgs::Float64{1.0}), "data: 1.0\n");
  EXPECT_EQ(toText(std_msgs::Float64MultiArray{{0.5, 2.0}}), "data: [0.5, 2.0]\n");
  EXPECT_EQ(toText(threeJoints()),
            "stamp: 0.5\n"
            "name: [j1, j2, j3]\n"
            "position: [0.1, -0.2, 3.0]\n"
            "velocity: [1.0, 0.0, -1.5]\n"
            "effort: [10.0, 20.0, 30.0]\n");
  // JSON that lost its field order (nlohmann::json sorts keys) prints in ROS order.
  EXPECT_EQ(messageToText("control_msgs/JointControllerState", toJson(control_msgs::JointControllerState{})),
            "stamp: 0.0\nset_point: 0.0\nprocess_value: 0.0\nprocess_value_dot: 0.0\nerror: 0.0\n"
            "time_step: 0.0\ncommand: 0.0\np: 0.0\ni: 0.0\nd: 0.0\ni_clamp: 0.0\nantiwindup: False\n");
}

TEST(Messages, CsvColumnsAreFlattened) {
  EXPECT_EQ(csvHeader(std_msgs::Float64{1.0}), "time,data");
  EXPECT_EQ(csvRow(std_msgs::Float64{1.0}, Time(0.01)), "0.01,1.0");
  EXPECT_EQ(csvHeader(std_msgs::Float64MultiArray{{1.0, 2.0}}), "time,data[0],data[1]");
  EXPECT_EQ(csvRow(std_msgs::Float64MultiArray{{1.0, 2.0}}, Time(2.0)), "2.0,1.0,2.0");
  const sensor_msgs::JointState joints = threeJoints();
  EXPECT_EQ(csvHeader(joints),
            "time,j1.position,j1.velocity,j1.effort,j2.position,j2.velocity,j2.effort,"
            "j3.position,j3.velocity,j3.effort");
  EXPECT_EQ(csvRow(joints, Time(0.5)), "0.5,0.1,1.0,10.0,-0.2,0.0,20.0,3.0,-1.5,30.0");
  control_msgs::JointControllerState state;
  state.set_point = 1.0;
  state.antiwindup = true;
  EXPECT_EQ(csvHeader(state),
            "time,set_point,process_value,process_value_dot,error,time_step,command,p,i,d,i_clamp,antiwindup");
  EXPECT_EQ(csvRow(state, Time(0.1)), "0.1,1.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,1");
}

TEST(Messages, FormatDoubleIsShortestRoundTrip) {
  EXPECT_EQ(formatDouble(1.0), "1.0");
  EXPECT_EQ(formatDouble(0.1), "0.1");
  EXPECT_EQ(formatDouble(-10.0), "-10.0");
  EXPECT_EQ(formatDouble(1e-7), "1e-07");
  EXPECT_EQ(formatDouble(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(formatDouble(-std::numeric_limits<double>::infinity()), "-inf");
  EXPECT_EQ(std::stod(formatDouble(0.30000000000000004)), 0.30000000000000004);
}

}  // namespace
}  // namespace servoloop::node

namespace servoloop::node {
namespace {

// NaN, infinities and numbers past a double's range cannot travel as JSON (they
// would arrive as null): the text a user typed is refused, naming the field
// and saying what is wrong with the number.
TEST(Messages, NumbersNoJsonCarriesAreNamedWithTheirField) {
  const auto errorOf = [](const std::string& text, const std::string& source) -> std::string {
    try {
      parseMessageText(text, source);
    } catch (const Error& e) {
      return e.what();
    }
    return "(accepted)";
  };
  EXPECT_EQ(errorOf("1e309", "VALUE").rfind(
                "VALUE: the value: 1e309 is out of range of a double (the largest is 1.8e308)", 0),
            0u)
      << errorOf("1e309", "VALUE");
  EXPECT_NE(errorOf("{data: .inf}", "VALUE").find("VALUE: field 'data': .inf is infinite"), std::string::npos);
  EXPECT_NE(errorOf("{data: [1, -.inf]}", "VALUE").find("VALUE: field 'data[1]': -.inf is infinite"),
            std::string::npos);
  EXPECT_NE(errorOf("{trajectory: {points: [{positions: [0, .nan]}]}}", "GOAL")
                .find("GOAL: field 'trajectory.points[0].positions[1]': .nan is not a number"),
            std::string::npos);
  EXPECT_NE(errorOf("{data: -1e400}", "VALUE").find("-1e400 is out of range of a double"), std::string::npos);
  // Finite numbers, and the words as strings, pass.
  EXPECT_EQ(parseMessageText("{data: 1.7e308}")["data"].get<double>(), 1.7e308);
  EXPECT_EQ(parseMessageText("{name: '.nan'}")["name"], ".nan");
}

}  // namespace
}  // namespace servoloop::node
