// readGazeboSensors: every form of IMU, force-torque and contact sensor a URDF
// gives Gazebo (SDFormat <sensor>s, the gazebo_ros sensor and model plugins,
// PR2's pre-1.0 forms) read with its values, the sensors Gazebo knows but
// servoloop does not simulate left out with one warning each, and one
// ConfigError naming the element and the value for every mistake.
#include "servoloop/description/gazebo_sensors.hpp"

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "expect_contains.hpp"
#include "log_capture.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/description/simulatable_urdf.hpp"

namespace servoloop {
namespace {

// (Names carry "gz": this file shares a unity batch with the other description tests.)
const std::string kGzInertial = R"(<inertial><mass value="1"/>
  <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>)";
const std::string kGzBox = R"(<geometry><box size="0.1 0.1 0.1"/></geometry>)";

std::string gzJoint(const std::string& name, const std::string& type, const std::string& parent,
                    const std::string& child) {
  return "<joint name=\"" + name + "\" type=\"" + type + "\"><parent link=\"" + parent + "\"/><child link=\"" + child +
         "\"/><axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>";
}

// base -+- imu_link (imu_joint, fixed; massless, so kept as Gazebo keeps it)
//       +- arm (arm_joint) -+- tool (wrist_ft, fixed)
//       |                   +- [ghost (ghost_joint; massless, so left out)]
//       +- bumper (bumper_joint, fixed; its collision is named "bumper_shell")
// with `gazebo` (the <gazebo> blocks) at the end.
std::string gzRobot(const std::string& gazebo, bool with_ghost = false) {
  return R"(<?xml version="1.0"?><robot name="sensor_bot">
    <link name="base">)" + kGzInertial + "<collision>" + kGzBox + R"(</collision></link>
    <link name="imu_link"/>
    <link name="arm">)" + kGzInertial + "<collision>" + kGzBox + R"(</collision></link>
    <link name="tool">)" + kGzInertial + R"(</link>
    <link name="bumper">)" + kGzInertial + R"(<collision name="bumper_shell">)" + kGzBox + R"(</collision></link>)" +
         gzJoint("imu_joint", "fixed", "base", "imu_link") + gzJoint("arm_joint", "revolute", "base", "arm") +
         gzJoint("wrist_ft", "fixed", "arm", "tool") + gzJoint("bumper_joint", "fixed", "base", "bumper") +
         (with_ghost ? "<link name=\"ghost\"/>" + gzJoint("ghost_joint", "revolute", "arm", "ghost") : "") + gazebo +
         "</robot>";
}

// The sensors of gzRobot(gazebo), read as the simulation reads them: from
// the text Gazebo-style pruning leaves and the model parsed from it.
std::vector<SensorDescription> gzSensorsOf(const std::string& gazebo) {
  const std::string xml = simulatableUrdf(gzRobot(gazebo), "s.urdf").xml;
  return readGazeboSensors(xml, *parseRobotModel(xml, "s.urdf"), "s.urdf");
}

// The one sensor of gzRobot(gazebo).
SensorDescription gzOnlySensorOf(const std::string& gazebo) {
  const std::vector<SensorDescription> sensors = gzSensorsOf(gazebo);
  EXPECT_EQ(sensors.size(), 1u);
  return sensors.empty() ? SensorDescription{} : sensors.front();
}

// The ConfigError message reading gzRobot(gazebo) gives; "" (and a test
// failure) when it gives none.
std::string gzErrorOf(const std::string& gazebo) {
  try {
    gzSensorsOf(gazebo);
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a ConfigError for " << gazebo;
  return "";
}

// An imu sensor on imu_link with `body` inside.
std::string gzImu(const std::string& body, const std::string& name = "imu") {
  return "<gazebo reference=\"imu_link\"><sensor name=\"" + name + "\" type=\"imu\">" + body + "</sensor></gazebo>";
}

std::string gzNoise(double mean, double stddev, double bias_mean, double bias_stddev) {
  return "<noise type=\"gaussian\"><mean>" + std::to_string(mean) + "</mean><stddev>" + std::to_string(stddev) +
         "</stddev><bias_mean>" + std::to_string(bias_mean) + "</bias_mean><bias_stddev>" +
         std::to_string(bias_stddev) + "</bias_stddev></noise>";
}

void gzExpectNoise(const GaussianNoise& noise, double mean, double stddev, double bias_mean, double bias_stddev) {
  EXPECT_DOUBLE_EQ(noise.mean, mean);
  EXPECT_DOUBLE_EQ(noise.stddev, stddev);
  EXPECT_DOUBLE_EQ(noise.bias_mean, bias_mean);
  EXPECT_DOUBLE_EQ(noise.bias_stddev, bias_stddev);
}

void gzExpectStddevs(const std::array<GaussianNoise, 3>& noise, double x, double y, double z) {
  EXPECT_DOUBLE_EQ(noise[0].stddev, x);
  EXPECT_DOUBLE_EQ(noise[1].stddev, y);
  EXPECT_DOUBLE_EQ(noise[2].stddev, z);
}

TEST(GazeboSensors, TypeNames) {
  EXPECT_STREQ(toString(SensorType::imu), "imu");
  EXPECT_STREQ(toString(SensorType::force_torque), "force_torque");
  EXPECT_STREQ(toString(SensorType::contact), "contact");
}

TEST(GazeboSensors, NoSensorsInARobotWithoutThem) {
  EXPECT_TRUE(gzSensorsOf("").empty());
  // Other <gazebo> settings and plugins are not sensors.
  EXPECT_TRUE(gzSensorsOf(R"(<gazebo reference="base"><mu1>0.5</mu1></gazebo>
    <gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so"/></gazebo>
    <gazebo><controller:gazebo_ros_p3d name="p3d" plugin="libgazebo_ros_p3d.so"><bodyName>base</bodyName>
    </controller:gazebo_ros_p3d></gazebo>)")
                  .empty());
}

TEST(GazeboSensors, ImuSensorWithSdfNoisePerAxis) {
  const SensorDescription imu = gzOnlySensorOf(gzImu(
      "<always_on>false</always_on><update_rate>200</update_rate><pose>0.1 -0.2 0.3 0 0.5 -1.5</pose>"
      "<imu><angular_velocity><x>" + gzNoise(0.1, 0.2, 0.3, 0.4) + "</x><y>" + gzNoise(0, 0.25, 0, 0) + "</y><z>" +
      gzNoise(0, 0.5, 0, 0) + "</z></angular_velocity><linear_acceleration><x>" + gzNoise(0, 1.5, 0.1, 0.2) +
      "</x><z>" + gzNoise(-0.5, 2, 0, 0) + "</z></linear_acceleration></imu>"));
  EXPECT_EQ(imu.name, "imu");
  EXPECT_EQ(imu.type, SensorType::imu);
  EXPECT_EQ(imu.reference, "imu_link");
  EXPECT_EQ(imu.element, "s.urdf: <gazebo reference='imu_link'><sensor name='imu'>");
  EXPECT_FALSE(imu.always_on);
  EXPECT_DOUBLE_EQ(imu.update_rate_hz, 200.0);
  EXPECT_EQ(imu.pose, (std::array<double, 6>{0.1, -0.2, 0.3, 0, 0.5, -1.5}));
  EXPECT_EQ(imu.topic, "");
  EXPECT_EQ(imu.frame_id, "imu_link");
  gzExpectNoise(imu.angular_velocity_noise[0], 0.1, 0.2, 0.3, 0.4);
  gzExpectNoise(imu.angular_velocity_noise[1], 0, 0.25, 0, 0);
  gzExpectNoise(imu.angular_velocity_noise[2], 0, 0.5, 0, 0);
  gzExpectNoise(imu.linear_acceleration_noise[0], 0, 1.5, 0.1, 0.2);
  EXPECT_TRUE(imu.linear_acceleration_noise[1].none());
  gzExpectNoise(imu.linear_acceleration_noise[2], -0.5, 2, 0, 0);
  EXPECT_TRUE(imu.orientation_noise.none());
  EXPECT_TRUE(imu.collisions.empty());
}

TEST(GazeboSensors, ImuDefaults) {
  const SensorDescription imu = gzOnlySensorOf(gzImu(""));
  EXPECT_TRUE(imu.always_on);
  EXPECT_DOUBLE_EQ(imu.update_rate_hz, 0.0);
  EXPECT_EQ(imu.pose, (std::array<double, 6>{}));
  for (const GaussianNoise& n : imu.angular_velocity_noise) EXPECT_TRUE(n.none());
  for (const GaussianNoise& n : imu.linear_acceleration_noise) EXPECT_TRUE(n.none());
}

TEST(GazeboSensors, ImuSdf14NoiseAppliesToEveryAxis) {
  const SensorDescription imu = gzOnlySensorOf(gzImu(R"(<imu><noise><type>gaussian</type>
    <rate><mean>0.01</mean><stddev>0.02</stddev><bias_mean>0.03</bias_mean><bias_stddev>0.04</bias_stddev></rate>
    <accel><mean>0.1</mean><stddev>0.2</stddev><bias_mean>0.3</bias_mean><bias_stddev>0.4</bias_stddev></accel>
    </noise></imu>)"));
  for (std::size_t axis = 0; axis < 3; ++axis) {
    gzExpectNoise(imu.angular_velocity_noise[axis], 0.01, 0.02, 0.03, 0.04);
    gzExpectNoise(imu.linear_acceleration_noise[axis], 0.1, 0.2, 0.3, 0.4);
  }
}

TEST(GazeboSensors, NoiseTypeNoneIsNoNoise) {
  const SensorDescription imu = gzOnlySensorOf(gzImu(
      R"(<imu><angular_velocity><x><noise type="none"><stddev>5</stddev></noise></x></angular_velocity></imu>)"));
  EXPECT_TRUE(imu.angular_velocity_noise[0].none());
  const SensorDescription old = gzOnlySensorOf(
      gzImu(R"(<imu><noise><type>none</type><rate><stddev>5</stddev></rate></noise></imu>)"));
  EXPECT_TRUE(old.angular_velocity_noise[2].none());
  // gaussian_quantized: gaussian (the quantization is not simulated).
  const SensorDescription quantized = gzOnlySensorOf(gzImu(
      R"(<imu><angular_velocity><y><noise type="gaussian_quantized"><stddev>0.5</stddev><precision>0.1</precision>
      </noise></y></angular_velocity></imu>)"));
  EXPECT_DOUBLE_EQ(quantized.angular_velocity_noise[1].stddev, 0.5);
}

TEST(GazeboSensors, ImuSensorPluginGivesTopicFrameRateAndNoise) {
  const SensorDescription imu = gzOnlySensorOf(gzImu(R"(<plugin name="imu_plugin" filename="libgazebo_ros_imu_sensor.so">
    <topicName>imu/data</topicName><frameName>imu_frame</frameName><updateRateHZ>50</updateRateHZ>
    <gaussianNoise>0.01</gaussianNoise></plugin>)"));
  EXPECT_EQ(imu.topic, "imu/data");
  EXPECT_EQ(imu.frame_id, "imu_frame");
  EXPECT_DOUBLE_EQ(imu.update_rate_hz, 50.0);
  gzExpectStddevs(imu.angular_velocity_noise, 0.01, 0.01, 0.01);
  gzExpectStddevs(imu.linear_acceleration_noise, 0.01, 0.01, 0.01);
  EXPECT_DOUBLE_EQ(imu.orientation_noise.stddev, 0.01);
}

TEST(GazeboSensors, ImuBlockNoiseAndUpdateRateWinOverThePlugins) {
  const SensorDescription imu = gzOnlySensorOf(gzImu(
      "<update_rate>400</update_rate><imu><angular_velocity><z>" + gzNoise(0, 0.3, 0, 0) +
      "</z></angular_velocity></imu><plugin name=\"p\" filename=\"libgazebo_ros_imu_sensor.so\">"
      "<updateRateHZ>50</updateRateHZ><gaussianNoise>0.01</gaussianNoise></plugin>"));
  EXPECT_DOUBLE_EQ(imu.update_rate_hz, 400.0);
  gzExpectStddevs(imu.angular_velocity_noise, 0, 0, 0.3);          // <imu> gave it
  gzExpectStddevs(imu.linear_acceleration_noise, 0.01, 0.01, 0.01);  // <imu> did not
  EXPECT_DOUBLE_EQ(imu.orientation_noise.stddev, 0.01);
}

TEST(GazeboSensors, ForceTorqueSensorOnAFixedJoint) {
  const SensorDescription ft = gzOnlySensorOf(R"(<gazebo reference="wrist_ft"><sensor name="wrist" type="force_torque">
    <update_rate>500</update_rate><force_torque><frame>parent</frame>
    <measure_direction>parent_to_child</measure_direction></force_torque>
    <plugin name="ft" filename="libgazebo_ros_ft_sensor.so"><topicName>wrist/wrench</topicName>
      <updateRate>100</updateRate><gaussianNoise>0.2</gaussianNoise></plugin></sensor></gazebo>)");
  EXPECT_EQ(ft.name, "wrist");
  EXPECT_EQ(ft.type, SensorType::force_torque);
  EXPECT_EQ(ft.reference, "wrist_ft");
  EXPECT_EQ(ft.frame_id, "tool");  // the joint's child link
  EXPECT_EQ(ft.frame, ForceTorqueFrame::parent);
  EXPECT_EQ(ft.measure_direction, ForceTorqueDirection::parent_to_child);
  EXPECT_DOUBLE_EQ(ft.update_rate_hz, 500.0);
  EXPECT_EQ(ft.topic, "wrist/wrench");
  EXPECT_DOUBLE_EQ(ft.wrench_noise.stddev, 0.2);

  const SensorDescription plain = gzOnlySensorOf(R"(<gazebo reference="arm_joint">
    <sensor name="shoulder" type="force_torque"><force_torque><frame>sensor</frame></force_torque>
    <plugin name="ft" filename="libgazebo_ros_ft_sensor.so"><updateRate>100</updateRate></plugin></sensor></gazebo>)");
  EXPECT_EQ(plain.frame_id, "arm");
  EXPECT_EQ(plain.frame, ForceTorqueFrame::sensor);
  EXPECT_EQ(plain.measure_direction, ForceTorqueDirection::child_to_parent);
  EXPECT_DOUBLE_EQ(plain.update_rate_hz, 100.0);  // the plugin's, the sensor giving none
  EXPECT_TRUE(plain.wrench_noise.none());

  const SensorDescription defaults = gzOnlySensorOf(
      R"(<gazebo reference="arm_joint"><sensor name="s" type="force_torque"/></gazebo>)");
  EXPECT_EQ(defaults.frame, ForceTorqueFrame::child);
  EXPECT_EQ(defaults.frame_id, "arm");
}

TEST(GazeboSensors, ContactSensorWithBumperPlugin) {
  const SensorDescription bumper = gzOnlySensorOf(R"(<gazebo reference="bumper"><sensor name="bump" type="contact">
    <update_rate>30</update_rate><contact><collision>bumper_collision</collision>
    <collision>bumper_collision_1</collision><collision>bumper_shell</collision></contact>
    <plugin name="b" filename="libgazebo_ros_bumper.so"><bumperTopicName>bumper_states</bumperTopicName>
    <frameName>world</frameName></plugin></sensor></gazebo>)");
  EXPECT_EQ(bumper.type, SensorType::contact);
  EXPECT_EQ(bumper.reference, "bumper");
  EXPECT_EQ(bumper.collisions, (std::vector<std::string>{"bumper_collision", "bumper_collision_1", "bumper_shell"}));
  EXPECT_EQ(bumper.topic, "bumper_states");
  EXPECT_EQ(bumper.frame_id, "world");
  EXPECT_DOUBLE_EQ(bumper.update_rate_hz, 30.0);

  const SensorDescription no_plugin = gzOnlySensorOf(R"(<gazebo reference="bumper"><sensor name="bump" type="contact">
    <contact><collision>bumper_collision</collision></contact></sensor></gazebo>)");
  EXPECT_EQ(no_plugin.frame_id, "world") << "gazebo_ros_bumper's default frameName";
  EXPECT_EQ(no_plugin.topic, "");
}

// Gazebo merges a link fixed to another into it, renaming its collisions
// "<body>_fixed_joint_lump__<link>_collision": the usual way to name a
// bumper's collision, from the bumper link or from the body.
TEST(GazeboSensors, ContactSensorTakesTheNamesFixedJointLumpingGives) {
  const SensorDescription on_bumper = gzOnlySensorOf(R"(<gazebo reference="bumper"><sensor name="b" type="contact">
    <contact><collision>base_fixed_joint_lump__bumper_collision</collision>
    <collision>base_fixed_joint_lump__bumper_shell</collision></contact></sensor></gazebo>)");
  EXPECT_EQ(on_bumper.collisions.size(), 2u);
  const SensorDescription on_base = gzOnlySensorOf(R"(<gazebo reference="base"><sensor name="b" type="contact">
    <contact><collision>base_collision</collision>
    <collision>base_fixed_joint_lump__bumper_collision_1</collision></contact></sensor></gazebo>)");
  EXPECT_EQ(on_base.collisions.size(), 2u);
}

// PR2's URDF, written for Gazebo before 1.0: <sensor:contact> with <geom>
// and a <controller:gazebo_ros_bumper>, and a <controller:gazebo_ros_imu>
// model plugin; its cameras and lasers are left out.
TEST(GazeboSensors, Pr2PreGazebo1Forms) {
  test::LogCapture log;
  const std::vector<SensorDescription> sensors = gzSensorsOf(R"(
  <gazebo reference="base">
    <selfCollide>true</selfCollide>
    <sensor:contact name="base_contact_sensor">
      <geom>base_geom</geom>
      <updateRate>100.0</updateRate>
      <controller:gazebo_ros_bumper name="base_gazebo_ros_bumper_controller" plugin="libgazebo_ros_bumper.so">
        <alwaysOn>true</alwaysOn>
        <updateRate>20.0</updateRate>
        <bumperTopicName>base_bumper</bumperTopicName>
        <interface:bumper name="base_bumper_iface"/>
      </controller:gazebo_ros_bumper>
    </sensor:contact>
    <sensor:camera name="high_def_sensor"><imageSize>2448 2050</imageSize></sensor:camera>
  </gazebo>
  <gazebo>
    <controller:gazebo_ros_imu name="imu_controller" plugin="libgazebo_ros_imu.so">
      <alwaysOn>false</alwaysOn>
      <updateRate>100.0</updateRate>
      <bodyName>imu_link</bodyName>
      <topicName>torso_lift_imu/data</topicName>
      <gaussianNoise>2.89e-08</gaussianNoise>
      <xyzOffsets>0 0 0.1</xyzOffsets>
      <rpyOffsets>0 3.14159265359 0</rpyOffsets>
      <interface:position name="imu_position"/>
    </controller:gazebo_ros_imu>
  </gazebo>)");
  ASSERT_EQ(sensors.size(), 2u);
  const SensorDescription& bumper = sensors[0];
  EXPECT_EQ(bumper.name, "base_contact_sensor");
  EXPECT_EQ(bumper.type, SensorType::contact);
  EXPECT_EQ(bumper.reference, "base");
  EXPECT_EQ(bumper.element, "s.urdf: <gazebo reference='base'><sensor:contact name='base_contact_sensor'>");
  EXPECT_EQ(bumper.collisions, std::vector<std::string>{"base_geom"});
  EXPECT_DOUBLE_EQ(bumper.update_rate_hz, 100.0);
  EXPECT_EQ(bumper.topic, "base_bumper");
  EXPECT_EQ(bumper.frame_id, "world");

  const SensorDescription& imu = sensors[1];
  EXPECT_EQ(imu.name, "imu_controller");
  EXPECT_EQ(imu.type, SensorType::imu);
  EXPECT_EQ(imu.reference, "imu_link");
  EXPECT_EQ(imu.element, "s.urdf: <gazebo><controller:gazebo_ros_imu name='imu_controller' plugin='libgazebo_ros_imu.so'>");
  EXPECT_FALSE(imu.always_on);
  EXPECT_DOUBLE_EQ(imu.update_rate_hz, 100.0);
  EXPECT_EQ(imu.topic, "torso_lift_imu/data");
  EXPECT_EQ(imu.frame_id, "imu_link");
  EXPECT_EQ(imu.pose, (std::array<double, 6>{0, 0, 0.1, 0, 3.14159265359, 0}));
  gzExpectStddevs(imu.angular_velocity_noise, 2.89e-08, 2.89e-08, 2.89e-08);
  gzExpectStddevs(imu.linear_acceleration_noise, 2.89e-08, 2.89e-08, 2.89e-08);
  EXPECT_DOUBLE_EQ(imu.orientation_noise.stddev, 2.89e-08);

  EXPECT_EQ(log.count("high_def_sensor"), 1u) << log.text();
  EXPECT_EQ(log.count("servoloop does not simulate"), 1u) << log.text();
}

TEST(GazeboSensors, GazeboRosImuModelPlugin) {
  const SensorDescription imu = gzOnlySensorOf(R"(<gazebo>
    <plugin name="imu_controller" filename="libgazebo_ros_imu.so">
      <updateRate>100</updateRate><bodyName>imu_link</bodyName><topicName>imu</topicName>
      <frameName>imu_optical</frameName><gaussianNoise>0.05</gaussianNoise>
      <xyzOffset>1 2 3</xyzOffset><rpyOffset>0.1 0.2 0.3</rpyOffset></plugin></gazebo>)");
  EXPECT_EQ(imu.name, "imu_controller");
  EXPECT_EQ(imu.element, "s.urdf: <gazebo><plugin name='imu_controller' filename='libgazebo_ros_imu.so'>");
  EXPECT_EQ(imu.reference, "imu_link");
  EXPECT_EQ(imu.frame_id, "imu_optical");
  EXPECT_EQ(imu.topic, "imu");
  EXPECT_TRUE(imu.always_on);
  EXPECT_DOUBLE_EQ(imu.update_rate_hz, 100.0);
  EXPECT_EQ(imu.pose, (std::array<double, 6>{1, 2, 3, 0.1, 0.2, 0.3}));
  gzExpectStddevs(imu.linear_acceleration_noise, 0.05, 0.05, 0.05);
  EXPECT_DOUBLE_EQ(imu.orientation_noise.stddev, 0.05);

  const SensorDescription plain = gzOnlySensorOf(
      R"(<gazebo><plugin name="imu2" filename="libgazebo_ros_imu.so"><bodyName>arm</bodyName></plugin></gazebo>)");
  EXPECT_EQ(plain.frame_id, "arm");  // frameName defaults to bodyName
  EXPECT_EQ(plain.topic, "");
  EXPECT_TRUE(plain.orientation_noise.none());
}

// Husky's IMU: hector's plugin with per-axis noise.
TEST(GazeboSensors, HectorImuModelPlugin) {
  const SensorDescription imu = gzOnlySensorOf(R"(<gazebo>
    <plugin name="imu_controller" filename="libhector_gazebo_ros_imu.so">
      <robotNamespace>/husky</robotNamespace>
      <updateRate>50.0</updateRate>
      <bodyName>base</bodyName>
      <frameId>imu_frame</frameId>
      <topicName>imu/data</topicName>
      <accelDrift>0.005 0.005 0.005</accelDrift>
      <accelGaussianNoise>0.005 0.006 0.007</accelGaussianNoise>
      <rateDrift>0.005 0.005 0.005 </rateDrift>
      <rateGaussianNoise> 0.001 </rateGaussianNoise>
      <headingDrift>0.005</headingDrift>
      <headingGaussianNoise>0.005</headingGaussianNoise>
      <xyzOffset>0 0 0.2</xyzOffset>
    </plugin></gazebo>)");
  EXPECT_EQ(imu.name, "imu_controller");
  EXPECT_EQ(imu.reference, "base");
  EXPECT_EQ(imu.frame_id, "imu_frame");
  EXPECT_EQ(imu.topic, "imu/data");
  EXPECT_DOUBLE_EQ(imu.update_rate_hz, 50.0);
  EXPECT_EQ(imu.pose, (std::array<double, 6>{0, 0, 0.2, 0, 0, 0}));
  gzExpectStddevs(imu.linear_acceleration_noise, 0.005, 0.006, 0.007);
  gzExpectStddevs(imu.angular_velocity_noise, 0.001, 0.001, 0.001);
  EXPECT_TRUE(imu.orientation_noise.none());

  // The older <gaussianNoise> takes the place of both, as hector reads it;
  // without <bodyName> the IMU is on the model's first link.
  const SensorDescription old = gzOnlySensorOf(R"(<gazebo><plugin name="imu" filename="libhector_gazebo_ros_imu.so">
      <accelGaussianNoise>0.5</accelGaussianNoise><gaussianNoise>0.02</gaussianNoise></plugin></gazebo>)");
  EXPECT_EQ(old.reference, "base");
  EXPECT_EQ(old.frame_id, "base");
  gzExpectStddevs(old.linear_acceleration_noise, 0.02, 0.02, 0.02);
  gzExpectStddevs(old.angular_velocity_noise, 0.02, 0.02, 0.02);
}

TEST(GazeboSensors, ForceTorqueModelPlugin) {
  const SensorDescription ft = gzOnlySensorOf(R"(<gazebo><plugin name="ft_sensor" filename="libgazebo_ros_ft_sensor.so">
    <updateRate>250</updateRate><topicName>ft_sensor_topic</topicName><jointName>wrist_ft</jointName>
    <gaussianNoise>0.3</gaussianNoise></plugin></gazebo>)");
  EXPECT_EQ(ft.name, "ft_sensor");
  EXPECT_EQ(ft.type, SensorType::force_torque);
  EXPECT_EQ(ft.reference, "wrist_ft");
  EXPECT_EQ(ft.frame_id, "tool");
  EXPECT_EQ(ft.topic, "ft_sensor_topic");
  EXPECT_DOUBLE_EQ(ft.update_rate_hz, 250.0);
  EXPECT_DOUBLE_EQ(ft.wrench_noise.stddev, 0.3);
  // The wrench gazebo_ros_ft_sensor publishes: SDFormat's defaults.
  EXPECT_EQ(ft.frame, ForceTorqueFrame::child);
  EXPECT_EQ(ft.measure_direction, ForceTorqueDirection::child_to_parent);
}

TEST(GazeboSensors, SensorsComeInDocumentOrder) {
  const std::vector<SensorDescription> sensors = gzSensorsOf(
      gzImu("", "first") +
      R"(<gazebo><plugin name="second" filename="libgazebo_ros_ft_sensor.so"><jointName>arm_joint</jointName></plugin>
      </gazebo>)" + gzImu("", "third"));
  ASSERT_EQ(sensors.size(), 3u);
  EXPECT_EQ(sensors[0].name, "first");
  EXPECT_EQ(sensors[1].name, "second");
  EXPECT_EQ(sensors[2].name, "third");
}

TEST(GazeboSensors, SensorsServoloopDoesNotSimulateAreLeftOutWithOneWarningEach) {
  test::LogCapture log;
  const std::vector<SensorDescription> sensors = gzSensorsOf(R"(
    <gazebo reference="base"><sensor name="cam" type="camera"><camera><horizontal_fov>1</horizontal_fov></camera>
      <plugin name="c" filename="libgazebo_ros_camera.so"/></sensor>
      <sensor name="laser" type="gpu_ray"/><sensor name="fix" type="gps"/></gazebo>
    <gazebo reference="arm"><sensor name="depth" type="depth"/></gazebo>)" + gzImu(""));
  ASSERT_EQ(sensors.size(), 1u);
  EXPECT_EQ(sensors[0].name, "imu");
  for (const char* name : {"'cam'", "'laser'", "'fix'", "'depth'"}) {
    EXPECT_EQ(log.count(std::string("<sensor name=") + name), 1u) << name << "\n" << log.text();
  }
  EXPECT_EQ(log.count("servoloop does not simulate"), 4u) << log.text();
  EXPECT_CONTAINS(log.text(), "s.urdf: <gazebo reference='base'><sensor name='cam'>");
  EXPECT_CONTAINS(log.text(), "gpu_ray");
}

TEST(GazeboSensors, ASensorOutsideAReferencedBlockIsLeftOutWithAWarning) {
  test::LogCapture log;
  EXPECT_TRUE(gzSensorsOf(R"(<gazebo><sensor name="lost" type="imu"/></gazebo>)").empty());
  EXPECT_EQ(log.count("<sensor name='lost'>"), 1u) << log.text();
  EXPECT_CONTAINS(log.text(), "reference='LINK'");
}

// ---------------------------------------------------------------------------
// Errors: one ConfigError naming the element, the value and the fix.

TEST(GazeboSensors, ReferenceNamingNoLink) {
  const std::string message = gzErrorOf(R"(<gazebo reference="nowhere"><sensor name="imu" type="imu"/></gazebo>)");
  EXPECT_CONTAINS(message, "s.urdf: <gazebo reference='nowhere'><sensor name='imu'>");
  EXPECT_CONTAINS(message, "no link 'nowhere'");
  EXPECT_CONTAINS(message, "massless");
}

TEST(GazeboSensors, ReferenceNamingAJointWhereALinkIsNeeded) {
  const std::string message =
      gzErrorOf(R"(<gazebo reference="arm_joint"><sensor name="s" type="contact"><contact>
        <collision>arm_collision</collision></contact></sensor></gazebo>)");
  EXPECT_CONTAINS(message, "s.urdf: <gazebo reference='arm_joint'><sensor name='s'>");
  EXPECT_CONTAINS(message, "'arm_joint' is a joint");
  EXPECT_CONTAINS(message, "child link 'arm'");
}

TEST(GazeboSensors, ReferenceNamingALinkWhereAJointIsNeeded) {
  const std::string message = gzErrorOf(R"(<gazebo reference="tool"><sensor name="ft" type="force_torque"/></gazebo>)");
  EXPECT_CONTAINS(message, "s.urdf: <gazebo reference='tool'><sensor name='ft'>");
  EXPECT_CONTAINS(message, "'tool' is a link");
  EXPECT_CONTAINS(message, "'wrist_ft'");
}

TEST(GazeboSensors, ReferenceNamingNoJoint) {
  const std::string message = gzErrorOf(R"(<gazebo reference="elbow"><sensor name="ft" type="force_torque"/></gazebo>)");
  EXPECT_CONTAINS(message, "<gazebo reference='elbow'><sensor name='ft'>");
  EXPECT_CONTAINS(message, "no joint 'elbow'");
}

// ghost is massless and moving: pruning leaves it (and ghost_joint) out.
TEST(GazeboSensors, ReferenceToALinkPruningLeftOut) {
  test::LogCapture log;  // (pruning's warning)
  const std::string blocks = R"(<gazebo reference="ghost"><sensor name="g" type="imu"/></gazebo>)";
  const std::string full = gzRobot(blocks, true);
  const std::string pruned = simulatableUrdf(full, "s.urdf").xml;
  const auto model = parseRobotModel(pruned, "s.urdf");
  // From the pruned text, the link is simply gone.
  try {
    readGazeboSensors(pruned, *model, "s.urdf");
    ADD_FAILURE() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_CONTAINS(e.what(), "s.urdf: <gazebo reference='ghost'><sensor name='g'>");
    EXPECT_CONTAINS(e.what(), "no link 'ghost'");
    EXPECT_CONTAINS(e.what(), "may have been left out because it is massless");
  }
  // From the full text, it is known to have been left out.
  try {
    readGazeboSensors(full, *model, "s.urdf");
    ADD_FAILURE() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_CONTAINS(e.what(), "<gazebo reference='ghost'><sensor name='g'>");
    EXPECT_CONTAINS(e.what(), "link 'ghost' was left out");
    EXPECT_CONTAINS(e.what(), "<inertial>");
  }
  const std::string joint_blocks = R"(<gazebo reference="ghost_joint"><sensor name="g" type="force_torque"/></gazebo>)";
  try {
    readGazeboSensors(gzRobot(joint_blocks, true), *model, "s.urdf");
    ADD_FAILURE() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_CONTAINS(e.what(), "joint 'ghost_joint' was left out");
  }
}

TEST(GazeboSensors, MissingNameOrType) {
  const std::string no_name = gzErrorOf(R"(<gazebo reference="imu_link"><sensor type="imu"/></gazebo>)");
  EXPECT_CONTAINS(no_name, "s.urdf: <gazebo reference='imu_link'><sensor>");
  EXPECT_CONTAINS(no_name, "no name");
  const std::string empty_name = gzErrorOf(R"(<gazebo reference="imu_link"><sensor name=" " type="imu"/></gazebo>)");
  EXPECT_CONTAINS(empty_name, "no name");
  const std::string no_type = gzErrorOf(R"(<gazebo reference="imu_link"><sensor name="s"/></gazebo>)");
  EXPECT_CONTAINS(no_type, "<sensor name='s'>");
  EXPECT_CONTAINS(no_type, "no type");
  const std::string plugin =
      gzErrorOf(R"(<gazebo><plugin filename="libgazebo_ros_imu.so"><bodyName>base</bodyName></plugin></gazebo>)");
  EXPECT_CONTAINS(plugin, "s.urdf: <gazebo><plugin filename='libgazebo_ros_imu.so'>");
  EXPECT_CONTAINS(plugin, "no name");
}

TEST(GazeboSensors, DuplicateName) {
  const std::string message = gzErrorOf(
      gzImu("", "twin") + R"(<gazebo reference="base"><sensor name="twin" type="contact"><contact>
      <collision>base_collision</collision></contact></sensor></gazebo>)");
  EXPECT_CONTAINS(message, "s.urdf: <gazebo reference='base'><sensor name='twin'>");
  EXPECT_CONTAINS(message, "a second sensor named 'twin'");
  EXPECT_CONTAINS(message, "<gazebo reference='imu_link'><sensor name='twin'>");
  // A model plugin's sensor shares the names.
  const std::string plugin = gzErrorOf(
      gzImu("", "imu_controller") +
      R"(<gazebo><plugin name="imu_controller" filename="libgazebo_ros_imu.so"><bodyName>base</bodyName></plugin></gazebo>)");
  EXPECT_CONTAINS(plugin, "<gazebo><plugin name='imu_controller'");
  EXPECT_CONTAINS(plugin, "a second sensor named 'imu_controller'");
}

TEST(GazeboSensors, PluginsOfOneNameOnTopicsOfTheirOwnAreTwoSensors) {
  // Kinova's arms: every joint's gazebo_ros_ft_sensor plugin is named
  // "ft_sensor", each with its own topic.
  const auto sensors = gzSensorsOf(
      R"(<gazebo><plugin name="ft_sensor" filename="libgazebo_ros_ft_sensor.so"><topicName>a_ft</topicName>
      <jointName>arm_joint</jointName></plugin></gazebo>
      <gazebo><plugin name="ft_sensor" filename="libgazebo_ros_ft_sensor.so"><topicName>b_ft</topicName>
      <jointName>arm_joint</jointName></plugin></gazebo>)");
  ASSERT_EQ(sensors.size(), 2u);
  EXPECT_EQ(sensors[0].topic, "a_ft");
  EXPECT_EQ(sensors[1].topic, "b_ft");
  // One topic twice is still an error, naming the topic.
  const std::string message = gzErrorOf(
      R"(<gazebo><plugin name="ft_a" filename="libgazebo_ros_ft_sensor.so"><topicName>same</topicName>
      <jointName>arm_joint</jointName></plugin></gazebo>
      <gazebo><plugin name="ft_b" filename="libgazebo_ros_ft_sensor.so"><topicName>/same</topicName>
      <jointName>arm_joint</jointName></plugin></gazebo>)");
  EXPECT_CONTAINS(message, "a second sensor publishing on '/same'");
  EXPECT_CONTAINS(message, "<gazebo><plugin name='ft_a'");
}

TEST(GazeboSensors, UnknownTypeListsTheTypes) {
  const std::string message = gzErrorOf(R"(<gazebo reference="base"><sensor name="s" type="lidarx"/></gazebo>)");
  EXPECT_CONTAINS(message, "s.urdf: <gazebo reference='base'><sensor name='s'>");
  EXPECT_CONTAINS(message, "type 'lidarx'");
  EXPECT_CONTAINS(message, "imu, force_torque and contact");
  EXPECT_CONTAINS(message, "camera, multicamera, depth, ray, gpu_ray");
  EXPECT_CONTAINS(gzErrorOf(R"(<gazebo reference="base"><sensor:sonic name="s"/></gazebo>)"), "type 'sonic'");
}

TEST(GazeboSensors, BadForceTorqueFrameOrDirection) {
  const std::string frame = gzErrorOf(R"(<gazebo reference="wrist_ft"><sensor name="ft" type="force_torque">
    <force_torque><frame>world</frame></force_torque></sensor></gazebo>)");
  EXPECT_CONTAINS(frame, "s.urdf: <gazebo reference='wrist_ft'><sensor name='ft'> <force_torque><frame> 'world'");
  EXPECT_CONTAINS(frame, "child, parent or sensor");
  const std::string direction = gzErrorOf(R"(<gazebo reference="wrist_ft"><sensor name="ft" type="force_torque">
    <force_torque><measure_direction>inward</measure_direction></force_torque></sensor></gazebo>)");
  EXPECT_CONTAINS(direction, "<force_torque><measure_direction> 'inward'");
  EXPECT_CONTAINS(direction, "child_to_parent");
}

TEST(GazeboSensors, BadUpdateRate) {
  for (const char* rate : {"-5", "inf", "nan", "fast", "", "1e999"}) {
    const std::string message = gzErrorOf(gzImu(std::string("<update_rate>") + rate + "</update_rate>"));
    EXPECT_CONTAINS(message, std::string("<sensor name='imu'> <update_rate> '") + rate + "'");
    EXPECT_CONTAINS(message, "finite number of Hz >= 0");
  }
  const std::string plugin = gzErrorOf(
      gzImu(R"(<plugin name="p" filename="libgazebo_ros_imu_sensor.so"><updateRateHZ>-1</updateRateHZ></plugin>)"));
  EXPECT_CONTAINS(plugin, "<sensor name='imu'> <plugin><updateRateHZ> '-1'");
  const std::string model = gzErrorOf(
      R"(<gazebo><plugin name="ft" filename="libgazebo_ros_ft_sensor.so"><jointName>arm_joint</jointName>
      <updateRate>often</updateRate></plugin></gazebo>)");
  EXPECT_CONTAINS(model, "<gazebo><plugin name='ft' filename='libgazebo_ros_ft_sensor.so'> <updateRate> 'often'");
  const std::string legacy = gzErrorOf(R"(<gazebo reference="base"><sensor:contact name="c"><geom>base_geom</geom>
      <updateRate>-3</updateRate></sensor:contact></gazebo>)");
  EXPECT_CONTAINS(legacy, "<sensor:contact name='c'> <updateRate> '-3'");
}

TEST(GazeboSensors, BadNoise) {
  const std::string stddev = gzErrorOf(gzImu(
      R"(<imu><angular_velocity><y><noise type="gaussian"><stddev>-0.1</stddev></noise></y></angular_velocity></imu>)"));
  EXPECT_CONTAINS(stddev, "<sensor name='imu'> <imu><angular_velocity><y><noise><stddev> '-0.1'");
  EXPECT_CONTAINS(stddev, "standard deviation must be a finite number >= 0");
  const std::string bias = gzErrorOf(gzImu(
      R"(<imu><linear_acceleration><z><noise type="gaussian"><bias_stddev>nan</bias_stddev></noise></z>
      </linear_acceleration></imu>)"));
  EXPECT_CONTAINS(bias, "<imu><linear_acceleration><z><noise><bias_stddev> 'nan'");
  const std::string mean = gzErrorOf(
      gzImu(R"(<imu><noise><type>gaussian</type><accel><mean>abc</mean></accel></noise></imu>)"));
  EXPECT_CONTAINS(mean, "<imu><noise><accel><mean> 'abc'");
  EXPECT_CONTAINS(mean, "finite number");
  const std::string type = gzErrorOf(gzImu(
      R"(<imu><angular_velocity><x><noise type="uniform"><stddev>1</stddev></noise></x></angular_velocity></imu>)"));
  EXPECT_CONTAINS(type, "<imu><angular_velocity><x><noise> type 'uniform'");
  EXPECT_CONTAINS(type, "gaussian");
  const std::string no_type = gzErrorOf(
      gzImu(R"(<imu><angular_velocity><x><noise><stddev>1</stddev></noise></x></angular_velocity></imu>)"));
  EXPECT_CONTAINS(no_type, "<noise> type ''");
  const std::string plugin = gzErrorOf(
      gzImu(R"(<plugin name="p" filename="libgazebo_ros_imu_sensor.so"><gaussianNoise>-1</gaussianNoise></plugin>)"));
  EXPECT_CONTAINS(plugin, "<sensor name='imu'> <plugin><gaussianNoise> '-1'");
  const std::string ft = gzErrorOf(R"(<gazebo><plugin name="ft" filename="libgazebo_ros_ft_sensor.so">
      <jointName>arm_joint</jointName><gaussianNoise>inf</gaussianNoise></plugin></gazebo>)");
  EXPECT_CONTAINS(ft, "<gazebo><plugin name='ft' filename='libgazebo_ros_ft_sensor.so'> <gaussianNoise> 'inf'");
  const std::string hector = gzErrorOf(R"(<gazebo><plugin name="h" filename="libhector_gazebo_ros_imu.so">
      <bodyName>base</bodyName><accelGaussianNoise>0.1 0.2</accelGaussianNoise></plugin></gazebo>)");
  EXPECT_CONTAINS(hector, "<gazebo><plugin name='h' filename='libhector_gazebo_ros_imu.so'> <accelGaussianNoise> '0.1 0.2'");
  EXPECT_CONTAINS(hector, "three (x y z)");
}

TEST(GazeboSensors, BadPoseOrOffset) {
  for (const char* pose : {"1 2 3", "1 2 3 4 5 x", "1 2 3 4 5 6 7", ""}) {
    const std::string message = gzErrorOf(gzImu(std::string("<pose>") + pose + "</pose>"));
    EXPECT_CONTAINS(message, std::string("<sensor name='imu'> <pose> '") + pose + "'");
    EXPECT_CONTAINS(message, "6 finite numbers");
  }
  const std::string offset = gzErrorOf(R"(<gazebo><plugin name="i" filename="libgazebo_ros_imu.so">
      <bodyName>base</bodyName><xyzOffset>1 2</xyzOffset></plugin></gazebo>)");
  EXPECT_CONTAINS(offset, "<gazebo><plugin name='i' filename='libgazebo_ros_imu.so'> <xyzOffset> '1 2'");
  EXPECT_CONTAINS(offset, "3 finite numbers");
  const std::string rpy = gzErrorOf(R"(<gazebo><controller:gazebo_ros_imu name="i" plugin="libgazebo_ros_imu.so">
      <bodyName>base</bodyName><rpyOffsets>0 0 pi</rpyOffsets></controller:gazebo_ros_imu></gazebo>)");
  EXPECT_CONTAINS(rpy, "<controller:gazebo_ros_imu name='i' plugin='libgazebo_ros_imu.so'> <rpyOffsets> '0 0 pi'");
}

TEST(GazeboSensors, BadAlwaysOn) {
  const std::string message = gzErrorOf(gzImu("<always_on>yes</always_on>"));
  EXPECT_CONTAINS(message, "<sensor name='imu'> <always_on> 'yes'");
  EXPECT_CONTAINS(message, "true, false, 1 or 0");
  EXPECT_TRUE(gzOnlySensorOf(gzImu("<always_on> 1 </always_on>")).always_on);
  EXPECT_FALSE(gzOnlySensorOf(gzImu("<always_on>0</always_on>")).always_on);
  const std::string plugin = gzErrorOf(R"(<gazebo><controller:gazebo_ros_imu name="i" plugin="libgazebo_ros_imu.so">
      <bodyName>base</bodyName><alwaysOn>on</alwaysOn></controller:gazebo_ros_imu></gazebo>)");
  EXPECT_CONTAINS(plugin, "<alwaysOn> 'on'");
}

TEST(GazeboSensors, ContactSensorCollisions) {
  const std::string none = gzErrorOf(R"(<gazebo reference="bumper"><sensor name="b" type="contact"/></gazebo>)");
  EXPECT_CONTAINS(none, "s.urdf: <gazebo reference='bumper'><sensor name='b'>");
  EXPECT_CONTAINS(none, "<contact><collision>");
  EXPECT_CONTAINS(none, "bumper_collision");
  const std::string other = gzErrorOf(R"(<gazebo reference="bumper"><sensor name="b" type="contact">
      <contact><collision>arm_collision</collision></contact></sensor></gazebo>)");
  EXPECT_CONTAINS(other, "<sensor name='b'> <contact><collision> 'arm_collision'");
  EXPECT_CONTAINS(other, "not a collision of link 'bumper'");
  // A link merged into base is not base's ancestor's: base is not fixed to arm.
  const std::string lump = gzErrorOf(R"(<gazebo reference="base"><sensor name="b" type="contact">
      <contact><collision>arm_fixed_joint_lump__base_collision</collision></contact></sensor></gazebo>)");
  EXPECT_CONTAINS(lump, "'arm_fixed_joint_lump__base_collision'");
  const std::string empty = gzErrorOf(R"(<gazebo reference="bumper"><sensor name="b" type="contact">
      <contact><collision> </collision></contact></sensor></gazebo>)");
  EXPECT_CONTAINS(empty, "<contact><collision> ''");
  const std::string legacy = gzErrorOf(R"(<gazebo reference="base"><sensor:contact name="c"><geom>arm_geom</geom>
      </sensor:contact></gazebo>)");
  EXPECT_CONTAINS(legacy, "<sensor:contact name='c'> <geom> 'arm_geom'");
}

TEST(GazeboSensors, ModelPluginReferences) {
  const std::string no_body =
      gzErrorOf(R"(<gazebo><plugin name="i" filename="libgazebo_ros_imu.so"><topicName>imu</topicName></plugin></gazebo>)");
  EXPECT_CONTAINS(no_body, "<gazebo><plugin name='i' filename='libgazebo_ros_imu.so'>");
  EXPECT_CONTAINS(no_body, "<bodyName>");
  const std::string bad_body =
      gzErrorOf(R"(<gazebo><plugin name="i" filename="libhector_gazebo_ros_imu.so"><bodyName>arm_joint</bodyName>
      </plugin></gazebo>)");
  EXPECT_CONTAINS(bad_body, "<gazebo><plugin name='i' filename='libhector_gazebo_ros_imu.so'> <bodyName> 'arm_joint'");
  EXPECT_CONTAINS(bad_body, "is a joint");
  const std::string no_joint =
      gzErrorOf(R"(<gazebo><plugin name="f" filename="libgazebo_ros_ft_sensor.so"><topicName>ft</topicName></plugin></gazebo>)");
  EXPECT_CONTAINS(no_joint, "<gazebo><plugin name='f' filename='libgazebo_ros_ft_sensor.so'>");
  EXPECT_CONTAINS(no_joint, "<jointName>");
  const std::string bad_joint =
      gzErrorOf(R"(<gazebo><plugin name="f" filename="libgazebo_ros_ft_sensor.so"><jointName>tool</jointName>
      </plugin></gazebo>)");
  EXPECT_CONTAINS(bad_joint, "<jointName> 'tool'");
  EXPECT_CONTAINS(bad_joint, "'tool' is a link");
}

}  // namespace
}  // namespace servoloop
