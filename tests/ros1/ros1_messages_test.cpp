// The bridge's message side without a ROS master: the message packages the
// project generates are ROS's own on the wire (md5sums as ROS Noetic's
// generated code publishes them), and every bridged type survives JSON → ROS →
// serialised bytes → ROS → JSON unchanged, NaN included.
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <control_msgs/JointControllerState.h>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <control_msgs/JointTrajectoryControllerState.h>
#include <controller_manager_msgs/ListControllers.h>
#include <controller_manager_msgs/SwitchController.h>
#include <gazebo_msgs/ApplyJointEffort.h>
#include <gazebo_msgs/ContactState.h>
#include <gazebo_msgs/ContactsState.h>
#include <gazebo_msgs/DeleteModel.h>
#include <gazebo_msgs/GetJointProperties.h>
#include <gazebo_msgs/GetModelState.h>
#include <gazebo_msgs/ModelState.h>
#include <gazebo_msgs/ModelStates.h>
#include <gazebo_msgs/SetModelState.h>
#include <gazebo_msgs/SpawnModel.h>
#include <gtest/gtest.h>
#include <ros/message_traits.h>
#include <ros/service_traits.h>

#include "controller_manager_services.hpp"
#include "gazebo_model_services.hpp"
#include "gazebo_services.hpp"
#include "parameter_bridge.hpp"
#include "ros_message_json.hpp"

namespace {

using nlohmann::json;

TEST(Ros1Messages, GeneratedPackagesHaveRosMd5sums) {
  // The md5sums ROS Noetic's control_msgs and controller_manager_msgs carry
  // (as published in their generated code for every client library).
  EXPECT_EQ(std::string(ros::message_traits::MD5Sum<control_msgs::JointControllerState>::value()),
            "987ad85e4756f3aef7f1e5e7fe0595d1");
  EXPECT_EQ(std::string(ros::message_traits::MD5Sum<control_msgs::JointTrajectoryControllerState>::value()),
            "10817c60c2486ef6b33e97dcd87f4474");
  EXPECT_EQ(std::string(ros::service_traits::MD5Sum<controller_manager_msgs::ListControllers>::value()),
            "1341feb2e63fa791f855565d0da950d8");
  EXPECT_EQ(std::string(ros::service_traits::MD5Sum<controller_manager_msgs::SwitchController>::value()),
            "b29a7abc673b2c54c14b54e50f8d06a5");
  // The action's messages, made by genaction from the .action file.
  EXPECT_EQ(std::string(ros::message_traits::MD5Sum<control_msgs::FollowJointTrajectoryGoal>::value()),
            "69636787b6ecbde4d61d711979bc7ecb");
  EXPECT_EQ(std::string(ros::message_traits::MD5Sum<control_msgs::FollowJointTrajectoryActionGoal>::value()),
            "cff5c1d533bf2f82dd0138d57f4304bb");
  // gazebo_msgs' services as Gazebo's ROS API serves them (since ROS Jade).
  EXPECT_EQ(std::string(ros::service_traits::MD5Sum<gazebo_msgs::ApplyJointEffort>::value()),
            "c0039811b8cc919490b3cff748cdf46b");
  EXPECT_EQ(std::string(ros::service_traits::MD5Sum<gazebo_msgs::GetJointProperties>::value()),
            "7b30be900f50aa21efec4a0ec92d91c9");
  EXPECT_EQ(std::string(ros::service_traits::MD5Sum<gazebo_msgs::GetModelState>::value()),
            "4c515e936d3319c9610c559c60bfc3d4");
  EXPECT_EQ(std::string(ros::service_traits::MD5Sum<gazebo_msgs::SetModelState>::value()),
            "5b3ab0281d4f5445def017e3a2e4a07b");
  EXPECT_EQ(std::string(ros::service_traits::MD5Sum<gazebo_msgs::SpawnModel>::value()),
            "9ed9c82c96abe1a00c3e8cdaeee24413");
  EXPECT_EQ(std::string(ros::service_traits::MD5Sum<gazebo_msgs::DeleteModel>::value()),
            "9ce56b4e9e54616de25d796dc972a262");
  EXPECT_EQ(std::string(ros::message_traits::MD5Sum<gazebo_msgs::ModelState>::value()),
            "9330fd35f2fcd82d457e54bd54e10593");
  EXPECT_EQ(std::string(ros::message_traits::MD5Sum<gazebo_msgs::ModelStates>::value()),
            "48c080191eb15c41858319b4d8a609c2");
  // gazebo_ros_bumper's contact sensor messages.
  EXPECT_EQ(std::string(ros::message_traits::MD5Sum<gazebo_msgs::ContactState>::value()),
            "48c0ffb054b8c444f870cecea1ee50d9");
  EXPECT_EQ(std::string(ros::message_traits::MD5Sum<gazebo_msgs::ContactsState>::value()),
            "acbcb1601a8e525bf72509f18e6f668d");
}

TEST(Ros1Messages, EveryBridgedTypeRoundTripsThroughRosSerialisation) {
  const json cases = {
      {"std_msgs/Float64", {{"data", 1.25}}},
      {"std_msgs/Bool", {{"data", true}}},
      {"std_msgs/Float64MultiArray", {{"data", {1.0, nullptr, -3.5}}}},
      {"geometry_msgs/Twist", {{"linear", {{"x", 0.5}, {"y", 0.0}, {"z", 0.0}}}, {"angular", {{"x", 0.0}, {"y", 0.0}, {"z", -1.5}}}}},
      {"sensor_msgs/JointState",
       {{"stamp", 12.5}, {"name", {"joint1", "joint2"}}, {"position", {0.1, -0.2}}, {"velocity", {0.0, 3.0}},
        {"effort", {nullptr, 4.13}}}},
      {"control_msgs/JointControllerState",
       {{"stamp", 3.131}, {"set_point", 1.0}, {"process_value", 0.98}, {"process_value_dot", 0.01},
        {"error", -0.02}, {"time_step", 0.001}, {"command", -4.13}, {"p", 100.0}, {"i", 0.01}, {"d", 10.0},
        {"i_clamp", 0.0}, {"antiwindup", false}}},
      {"trajectory_msgs/JointTrajectory",
       {{"stamp", 0.0}, {"joint_names", {"a", "b"}},
        {"points", {{{"positions", {1.0, 2.0}}, {"velocities", json::array()}, {"accelerations", json::array()},
                     {"effort", json::array()}, {"time_from_start", 1.5}}}}}},
      {"nav_msgs/Odometry",
       {{"stamp", 2.0}, {"frame_id", "odom"}, {"child_frame_id", "base_link"},
        {"pose", {{"position", {{"x", 1.0}, {"y", 2.0}, {"z", 0.0}}},
                  {"orientation", {{"x", 0.0}, {"y", 0.0}, {"z", 0.5}, {"w", 0.75}}},
                  {"covariance", std::vector<double>(36, 0.25)}}},
        {"twist", {{"linear", {{"x", 0.1}, {"y", 0.0}, {"z", 0.0}}}, {"angular", {{"x", 0.0}, {"y", 0.0}, {"z", 0.2}}},
                   {"covariance", std::vector<double>(36, 0.5)}}}}},
      {"tf2_msgs/TFMessage",
       {{"transforms", {{{"stamp", 1.0}, {"frame_id", "odom"}, {"child_frame_id", "base_link"},
                         {"translation", {{"x", 1.0}, {"y", 0.0}, {"z", 0.0}}},
                         {"rotation", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}, {"w", 1.0}}}}}}}},
      {"diagnostic_msgs/DiagnosticArray",
       {{"stamp", 4.0}, {"status", {{{"level", 2}, {"name", "loop"}, {"message", "protective stop"},
                                      {"hardware_id", "one_DOF_robot"},
                                      {"values", {{{"key", "overruns"}, {"value", "3"}}}}}}}}},
      {"gazebo_msgs/ModelStates",
       {{"name", {"ground_plane", "crate"}},
        {"pose", {{{"position", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}}},
                   {"orientation", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}, {"w", 1.0}}}},
                  {{"position", {{"x", 1.5}, {"y", -0.25}, {"z", nullptr}}},
                   {"orientation", {{"x", 0.0}, {"y", 0.0}, {"z", 0.6}, {"w", 0.8}}}}}},
        {"twist", {{{"linear", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}}}, {"angular", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}}}},
                   {{"linear", {{"x", 0.1}, {"y", 0.0}, {"z", -2.0}}}, {"angular", {{"x", 0.0}, {"y", 0.0}, {"z", 2.0}}}}}}}},
      {"geometry_msgs/WrenchStamped",
       {{"stamp", 0.25}, {"frame_id", "wrist_ft"},
        {"wrench", {{"force", {{"x", 1.5}, {"y", -2.0}, {"z", 9.81}}}, {"torque", {{"x", 0.0}, {"y", nullptr}, {"z", -0.5}}}}}}},
      // An IMU without orientation: covariance[0] = -1, as ROS says for "not measured".
      {"sensor_msgs/Imu",
       {{"stamp", 1.5}, {"frame_id", "imu_link"},
        {"orientation", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}, {"w", 0.0}}},
        {"orientation_covariance", {-1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0}},
        {"angular_velocity", {{"x", 0.1}, {"y", -0.2}, {"z", 0.3}}},
        {"angular_velocity_covariance", {1e-4, 0.0, 0.0, 0.0, 1e-4, 0.0, 0.0, 0.0, 1e-4}},
        {"linear_acceleration", {{"x", 0.0}, {"y", 0.0}, {"z", 9.81}}},
        {"linear_acceleration_covariance", {0.01, 0.0, 0.0, 0.0, 0.01, 0.0, 0.0, 0.0, nullptr}}}},
      {"gazebo_msgs/ContactsState",
       {{"stamp", 3.0}, {"frame_id", "world"},
        {"states",
         {{{"info", "box on the ground"}, {"collision1_name", "box::link::collision"},
           {"collision2_name", "ground_plane::link::collision"},
           {"wrenches", {{{"force", {{"x", 0.0}, {"y", 0.0}, {"z", 4.9}}}, {"torque", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}}}},
                         {{"force", {{"x", 0.0}, {"y", 0.0}, {"z", 4.9}}}, {"torque", {{"x", 0.1}, {"y", 0.0}, {"z", 0.0}}}}}},
           {"total_wrench", {{"force", {{"x", 0.0}, {"y", 0.0}, {"z", 9.8}}}, {"torque", {{"x", 0.1}, {"y", 0.0}, {"z", 0.0}}}}},
           {"contact_positions", {{{"x", 0.05}, {"y", 0.05}, {"z", 0.0}}, {{"x", -0.05}, {"y", -0.05}, {"z", 0.0}}}},
           {"contact_normals", {{{"x", 0.0}, {"y", 0.0}, {"z", 1.0}}, {{"x", 0.0}, {"y", 0.0}, {"z", 1.0}}}},
           {"depths", {1e-4, 2e-4}}},
          {{"info", ""}, {"collision1_name", "box::link::collision"}, {"collision2_name", "wall::link::collision"},
           {"wrenches", json::array()},
           {"total_wrench", {{"force", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}}}, {"torque", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}}}}},
           {"contact_positions", json::array()}, {"contact_normals", json::array()}, {"depths", json::array()}}}}}},
  };
  for (const auto& [type, msg] : cases.items()) {
    SCOPED_TRACE(type);
    EXPECT_EQ(servoloop::ros1::roundTrip(type, msg), msg);
  }
  // + control_msgs/JointTrajectoryControllerState, in the next test.
  EXPECT_EQ(servoloop::ros1::bridgedTypeNames().size(), cases.size() + 1) << "a bridged type has no round-trip case";
}

TEST(Ros1Messages, TrajectoryControllerStateRoundTrips) {
  const json point = {{"positions", {1.0}}, {"velocities", {0.5}}, {"accelerations", {0.0}}, {"effort", json::array()},
                      {"time_from_start", 0.25}};
  const json msg = {{"stamp", 1.5}, {"joint_names", {"j"}}, {"desired", point}, {"actual", point}, {"error", point}};
  EXPECT_EQ(servoloop::ros1::roundTrip("control_msgs/JointTrajectoryControllerState", msg), msg);
}

TEST(Ros1Messages, CommandsGoToTheNodeAndStatesComeFromIt) {
  for (const char* command : {"std_msgs/Float64", "std_msgs/Float64MultiArray", "std_msgs/Bool", "geometry_msgs/Twist",
                              "trajectory_msgs/JointTrajectory"}) {
    ASSERT_NE(servoloop::ros1::findBridgedType(command), nullptr) << command;
    EXPECT_TRUE(servoloop::ros1::findBridgedType(command)->command) << command;
  }
  for (const char* state : {"sensor_msgs/JointState", "control_msgs/JointControllerState", "nav_msgs/Odometry",
                            "tf2_msgs/TFMessage", "diagnostic_msgs/DiagnosticArray", "gazebo_msgs/ModelStates",
                            "sensor_msgs/Imu", "geometry_msgs/WrenchStamped", "gazebo_msgs/ContactsState"}) {
    ASSERT_NE(servoloop::ros1::findBridgedType(state), nullptr) << state;
    EXPECT_FALSE(servoloop::ros1::findBridgedType(state)->command) << state;
  }
  // /gazebo/model_states, as the node publishes it, round-trips.
  const json model_states = {
      {"name", {"one_DOF_robot"}},
      {"pose", {{{"position", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}}},
                 {"orientation", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}, {"w", 1.0}}}}}},
      {"twist", {{{"linear", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}}}, {"angular", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}}}}}}};
  EXPECT_EQ(servoloop::ros1::roundTrip("gazebo_msgs/ModelStates", model_states), model_states);
  EXPECT_EQ(servoloop::ros1::findBridgedType("gazebo_msgs/LinkStates"), nullptr);
  EXPECT_THROW(servoloop::ros1::roundTrip("gazebo_msgs/LinkStates", json::object()), std::invalid_argument);
}

TEST(Ros1Messages, ControllerStatesAndInterfacesUseRosControlNames) {
  EXPECT_STREQ(servoloop::ros1::rosControlState("running"), "running");
  EXPECT_STREQ(servoloop::ros1::rosControlState("stopped"), "stopped");
  EXPECT_STREQ(servoloop::ros1::rosControlState("initialized"), "initialized");
  EXPECT_STREQ(servoloop::ros1::rosControlState("constructed"), "initialized");
  EXPECT_STREQ(servoloop::ros1::rosControlState("failed"), "aborted");
  EXPECT_EQ(servoloop::ros1::rosControlInterfaceName("EffortJointInterface"), "hardware_interface::EffortJointInterface");
  EXPECT_EQ(servoloop::ros1::rosControlInterfaceName("my_robot::GripperInterface"), "my_robot::GripperInterface");
}

TEST(Ros1Messages, ParametersKeepTheirYamlTypes) {
  const XmlRpc::XmlRpcValue value = servoloop::ros1::yamlToXmlRpc(
      YAML::Load("{i: 100, d: 1.5, b: true, quoted: '2', s: effort_controllers/JointPositionController, l: [1, 2.5]}"));
  ASSERT_EQ(value.getType(), XmlRpc::XmlRpcValue::TypeStruct);
  XmlRpc::XmlRpcValue copy = value;
  EXPECT_EQ(copy["i"].getType(), XmlRpc::XmlRpcValue::TypeInt);
  EXPECT_EQ(static_cast<int>(copy["i"]), 100);
  EXPECT_EQ(copy["d"].getType(), XmlRpc::XmlRpcValue::TypeDouble);
  EXPECT_EQ(static_cast<double>(copy["d"]), 1.5);
  EXPECT_EQ(copy["b"].getType(), XmlRpc::XmlRpcValue::TypeBoolean);
  EXPECT_EQ(copy["quoted"].getType(), XmlRpc::XmlRpcValue::TypeString);
  EXPECT_EQ(static_cast<std::string>(copy["quoted"]), "2");
  EXPECT_EQ(static_cast<std::string>(copy["s"]), "effort_controllers/JointPositionController");
  ASSERT_EQ(copy["l"].getType(), XmlRpc::XmlRpcValue::TypeArray);
  EXPECT_EQ(copy["l"][0].getType(), XmlRpc::XmlRpcValue::TypeInt);
  EXPECT_EQ(static_cast<double>(copy["l"][1]), 2.5);
}

TEST(Ros1Messages, RosParametersGoBackAsYamlThatKeepsTheirTypes) {
  // What load_controller hands the node: each value as YAML text that loads
  // back with the type rosparam gave it.
  XmlRpc::XmlRpcValue value = servoloop::ros1::yamlToXmlRpc(YAML::Load(
      "{p: 500, d: 20.5, whole: 100.0, limit: .inf, on: true, quoted: '2', letter: 'y', joints: [a, b], "
      "third: 0.1}"));
  const YAML::Node back = YAML::Load(servoloop::ros1::xmlRpcToYaml(value));
  EXPECT_EQ(back["p"].as<int>(), 500);
  EXPECT_EQ(back["d"].as<double>(), 20.5);
  // A whole double stays a double (an integer conversion refuses it).
  EXPECT_EQ(back["whole"].as<double>(), 100.0);
  int as_int = 0;
  EXPECT_FALSE(YAML::convert<int>::decode(back["whole"], as_int)) << back["whole"].Scalar();
  EXPECT_EQ(back["limit"].as<double>(), std::numeric_limits<double>::infinity());
  EXPECT_TRUE(back["on"].as<bool>());
  EXPECT_EQ(back["quoted"].Tag(), "!");  // a quoted scalar: a string, not the number 2
  EXPECT_EQ(back["quoted"].as<std::string>(), "2");
  EXPECT_EQ(back["letter"].Tag(), "!");  // not yaml-cpp's boolean 'y'
  EXPECT_EQ(back["joints"].as<std::vector<std::string>>(), (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(back["third"].as<double>(), 0.1);  // every digit: the same double
}

// (name, YAML text) of each parameter to pass on.
std::vector<std::pair<std::string, std::string>> namesAndYaml(const std::vector<servoloop::ros1::ChangedParameter>& changed) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& parameter : changed) out.emplace_back(parameter.name, parameter.yaml);
  return out;
}

TEST(Ros1Messages, OnlyParametersChangedInRosSinceTheCopyArePassedOn) {
  // The bridge copied p 100, i 1 and the type; in ROS since: i set to 2 and
  // d added. Passed on: d and i (as YAML); p and the type are left to the
  // node (which may have changed them itself since).
  const YAML::Node copied = YAML::Load(
      "{robot: {ctrl: {type: effort_controllers/JointPositionController, pid: {p: 100.0, i: 1}}}}");
  XmlRpc::XmlRpcValue ros_value = servoloop::ros1::yamlToXmlRpc(
      YAML::Load("{type: effort_controllers/JointPositionController, pid: {p: 100.0, i: 2, d: 5.5}}"));
  std::map<std::string, std::string> synced;
  const auto changed = servoloop::ros1::changedParameters("/robot/ctrl", ros_value, copied, synced);
  EXPECT_EQ(namesAndYaml(changed), (std::vector<std::pair<std::string, std::string>>{{"/robot/ctrl/pid/d", "5.5"},
                                                                       {"/robot/ctrl/pid/i", "2"}}));
  // Nothing copied at all (a controller configured only in ROS): everything.
  EXPECT_EQ(servoloop::ros1::changedParameters("/robot/ctrl", ros_value, YAML::Node(), synced).size(), 4u);

  // i was passed on as 2 at a load; set back to 1 in ROS (the value the
  // bridge once copied), it differs from what the node has, so it goes again;
  // d, passed on as 5.5 and unchanged since, does not.
  synced["/robot/ctrl/pid/i"] = ros_value["pid"]["i"].toXml();
  synced["/robot/ctrl/pid/d"] = ros_value["pid"]["d"].toXml();
  ros_value["pid"]["i"] = 1;
  EXPECT_EQ(namesAndYaml(servoloop::ros1::changedParameters("/robot/ctrl", ros_value, copied, synced)),
            (std::vector<std::pair<std::string, std::string>>{{"/robot/ctrl/pid/i", "1"}}));
}

TEST(Ros1GazeboServices, EffortsAddUpOverTheirWindows) {
  servoloop::ros1::EffortSchedule schedule;
  schedule.apply(2.0, 0.0, -1.0, 1.0);   // from now (1.0 s), without end
  schedule.apply(0.5, 0.0, 0.5, 1.0);    // from now for 0.5 s: [1.0, 1.5)
  schedule.apply(-1.0, 2.0, 1.0, 1.0);   // later: [2.0, 3.0)
  schedule.apply(7.0, 0.0, 0.0, 1.0);    // duration 0: nothing, as in Gazebo
  EXPECT_EQ(schedule.sumAt(1.0), 2.5);
  EXPECT_EQ(schedule.sumAt(1.49), 2.5);
  EXPECT_EQ(schedule.sumAt(1.5), 2.0);
  EXPECT_EQ(schedule.sumAt(2.0), 1.0);
  EXPECT_EQ(schedule.sumAt(2.999), 1.0);
  EXPECT_EQ(schedule.sumAt(3.0), 2.0);
  EXPECT_EQ(schedule.sumAt(1e9), 2.0);
}

TEST(Ros1GazeboServices, JointTypesAndDampingComeFromTheUrdf) {
  const auto joints = servoloop::ros1::urdfJoints(R"(<robot name="r">
    <link name="a"/><link name="b"/><link name="c"/>
    <joint name="hinge" type="revolute"><parent link="a"/><child link="b"/><dynamics damping="0.7"/></joint>
    <joint name="wheel" type="continuous"><parent link="b"/><child link="c"/></joint>
    <joint name="slide" type="prismatic"><parent link="b"/><child link="c"/></joint>
    <joint name="glue" type="fixed"><parent link="a"/><child link="c"/></joint>
    <transmission name="t"><joint name="hinge"/></transmission>
  </robot>)");
  ASSERT_EQ(joints.size(), 4u);
  EXPECT_EQ(joints.at("hinge").gazebo_type, gazebo_msgs::GetJointProperties::Response::REVOLUTE);
  EXPECT_EQ(joints.at("hinge").damping, 0.7);
  EXPECT_EQ(joints.at("wheel").gazebo_type, gazebo_msgs::GetJointProperties::Response::CONTINUOUS);
  EXPECT_EQ(joints.at("wheel").damping, 0.0);
  EXPECT_EQ(joints.at("slide").gazebo_type, gazebo_msgs::GetJointProperties::Response::PRISMATIC);
  EXPECT_EQ(joints.at("glue").gazebo_type, gazebo_msgs::GetJointProperties::Response::FIXED);
  EXPECT_THROW(servoloop::ros1::urdfJoints("<robot"), std::runtime_error);
}

TEST(Ros1GazeboServices, SpawnPosesTurnIntoUrdfRollPitchYaw) {
  // The quaternion of R = Rz(yaw)·Ry(pitch)·Rx(roll), back to its angles.
  const double roll = 0.3, pitch = -0.4, yaw = 2.5;
  const double cr = std::cos(roll / 2), sr = std::sin(roll / 2);
  const double cp = std::cos(pitch / 2), sp = std::sin(pitch / 2);
  const double cy = std::cos(yaw / 2), sy = std::sin(yaw / 2);
  const double w = cr * cp * cy + sr * sp * sy;
  const double x = sr * cp * cy - cr * sp * sy;
  const double y = cr * sp * cy + sr * cp * sy;
  const double z = cr * cp * sy - sr * sp * cy;
  auto rpy = servoloop::ros1::rollPitchYaw(x, y, z, w);
  EXPECT_NEAR(rpy[0], roll, 1e-12);
  EXPECT_NEAR(rpy[1], pitch, 1e-12);
  EXPECT_NEAR(rpy[2], yaw, 1e-12);
  // Not normalised: the same rotation.
  rpy = servoloop::ros1::rollPitchYaw(2 * x, 2 * y, 2 * z, 2 * w);
  EXPECT_NEAR(rpy[2], yaw, 1e-12);
  // The zero quaternion (a ROS message left at its defaults): no rotation.
  EXPECT_EQ(servoloop::ros1::rollPitchYaw(0, 0, 0, 0), (std::array<double, 3>{0.0, 0.0, 0.0}));

  EXPECT_TRUE(servoloop::ros1::isWorldFrame(""));
  EXPECT_TRUE(servoloop::ros1::isWorldFrame("world"));
  EXPECT_TRUE(servoloop::ros1::isWorldFrame("map"));
  EXPECT_FALSE(servoloop::ros1::isWorldFrame("crate::base"));
}

}  // namespace
