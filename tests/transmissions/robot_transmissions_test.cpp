// RobotTransmissions: interface registration, propagation in all directions,
// implicit transmissions and lookups, on the seed robots and inline URDFs.
#include "servoloop/transmissions/robot_transmissions.hpp"

#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "servoloop/hardware_interface/actuator_interfaces.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/interface_manager.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/core/logging.hpp"

namespace hi = servoloop::hardware_interface;
namespace st = servoloop::transmissions;
using servoloop::ActuatorIndex;
using servoloop::JointIndex;

namespace {

constexpr double kTol = 1e-12;

std::string readSeed(const std::string& name) {
  std::ifstream file(std::string(SERVOLOOP_SEED_DIR) + "/" + name);
  EXPECT_TRUE(file.good()) << name;
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

std::unique_ptr<st::RobotTransmissions> fromUrdf(const std::string& xml, bool implicit = false) {
  st::RobotTransmissionsOptions options;
  options.implicit_simple_transmissions = implicit;
  options.source_name = "test.urdf";
  return st::RobotTransmissions::fromUrdf(xml, options);
}

// Two revolute joints: a 50:1 simple drive on "shoulder" (effort + position)
// and a differential wrist, plus an untransmitted "passive" joint.
const char* kArm = R"(<?xml version="1.0"?>
<robot name="arm">
  <link name="base"/><link name="upper"/><link name="w1"/><link name="w2"/><link name="tip"/>
  <joint name="shoulder" type="continuous"><parent link="base"/><child link="upper"/></joint>
  <joint name="pitch" type="continuous"><parent link="upper"/><child link="w1"/></joint>
  <joint name="roll" type="continuous"><parent link="w1"/><child link="w2"/></joint>
  <joint name="passive" type="continuous"><parent link="w2"/><child link="tip"/></joint>
  <transmission name="shoulder_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="shoulder">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>
    </joint>
    <actuator name="shoulder_motor"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
  <transmission name="wrist_trans">
    <type>transmission_interface/DifferentialTransmission</type>
    <joint name="pitch"><role>joint1</role><offset>-2</offset><mechanicalReduction>-2</mechanicalReduction>
      <hardwareInterface>VelocityJointInterface</hardwareInterface></joint>
    <joint name="roll"><role>joint2</role><offset>4</offset><mechanicalReduction>4</mechanicalReduction>
      <hardwareInterface>VelocityJointInterface</hardwareInterface></joint>
    <actuator name="wrist_left"><role>actuator1</role><mechanicalReduction>10</mechanicalReduction></actuator>
    <actuator name="wrist_right"><role>actuator2</role><mechanicalReduction>-20</mechanicalReduction></actuator>
  </transmission>
</robot>)";

}  // namespace

TEST(RobotTransmissions, SeedRobotRegistersItsInterfaces) {
  const auto rt = fromUrdf(readSeed("minimal_robot_description_w_jnt_ctl.urdf"));
  ASSERT_EQ(rt->numJoints(), 1u);
  ASSERT_EQ(rt->numActuators(), 1u);
  EXPECT_EQ(rt->jointName(JointIndex(0)), "joint1");
  EXPECT_EQ(rt->actuatorName(ActuatorIndex(0)), "motor1");
  EXPECT_TRUE(rt->implicitTransmissionJoints().empty());
  const auto& commands = rt->jointCommandInterfaces(rt->jointIndex("joint1"));
  EXPECT_TRUE(commands.effort);
  EXPECT_FALSE(commands.velocity);
  EXPECT_FALSE(commands.position);

  hi::InterfaceManager manager;
  rt->registerInterfaces(manager);
  EXPECT_EQ(manager.getNames(),
            (std::vector<std::string>{"ActuatorStateInterface", "EffortActuatorInterface",
                                      "EffortJointInterface", "JointStateInterface"}));
  ASSERT_NE(manager.get<hi::JointStateInterface>(), nullptr);
  ASSERT_NE(manager.get<hi::EffortJointInterface>(), nullptr);
  EXPECT_EQ(manager.get<hi::VelocityJointInterface>(), nullptr);
  EXPECT_EQ(manager.get<hi::PositionJointInterface>(), nullptr);
  EXPECT_EQ(manager.get<hi::JointStateInterface>()->getNames(), std::vector<std::string>{"joint1"});
  EXPECT_EQ(manager.get<hi::EffortActuatorInterface>()->getNames(),
            std::vector<std::string>{"motor1"});
}

TEST(RobotTransmissions, SeedRobotPropagatesThroughHandles) {
  const auto rt = fromUrdf(readSeed("minimal_robot_description_w_jnt_ctl.urdf"));
  hi::InterfaceManager manager;
  rt->registerInterfaces(manager);
  hi::JointHandle joint1 = manager.get<hi::EffortJointInterface>()->getHandle("joint1");
  hi::ActuatorHandle motor1 = manager.get<hi::EffortActuatorInterface>()->getHandle("motor1");

  // Read path: what the motor reports reaches the controller's handle.
  st::ActuatorValues& motor = rt->actuator(rt->actuatorIndex("motor1"));
  motor.position = 0.7;
  motor.velocity = -0.2;
  motor.effort = 1.5;
  rt->actuatorStateToJointState();
  EXPECT_NEAR(joint1.getPosition(), 0.7, kTol);
  EXPECT_NEAR(joint1.getVelocity(), -0.2, kTol);
  EXPECT_NEAR(joint1.getEffort(), 1.5, kTol);

  // Write path: the controller's effort reaches the motor (reduction 1).
  joint1.setCommand(3.25);
  rt->jointCommandToActuatorCommand();
  EXPECT_NEAR(motor1.getCommand(), 3.25, kTol);
  EXPECT_NEAR(motor.effort_command, 3.25, kTol);
}

TEST(RobotTransmissions, ImplicitTransmissionForRobotWithoutTransmissions) {
  auto sink_stream = std::make_shared<std::ostringstream>();
  auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(*sink_stream);
  servoloop::spdlogLogger().sinks().push_back(sink);
  const auto rt = fromUrdf(readSeed("minimal_robot_description.urdf"), /*implicit=*/true);
  servoloop::spdlogLogger().flush();
  servoloop::spdlogLogger().sinks().pop_back();

  ASSERT_EQ(rt->numJoints(), 1u);  // the fixed joint gets none
  EXPECT_EQ(rt->jointName(JointIndex(0)), "joint1");
  EXPECT_EQ(rt->actuatorName(ActuatorIndex(0)), "joint1_motor");
  EXPECT_EQ(rt->implicitTransmissionJoints(), std::vector<std::string>{"joint1"});
  EXPECT_TRUE(rt->jointCommandInterfaces(JointIndex(0)).effort);
  EXPECT_TRUE(rt->jointCommandInterfaces(JointIndex(0)).velocity);
  EXPECT_TRUE(rt->jointCommandInterfaces(JointIndex(0)).position);

  const std::string log = sink_stream->str();
  EXPECT_NE(log.find("joint1"), std::string::npos) << log;
  EXPECT_NE(log.find("implicit"), std::string::npos) << log;
  EXPECT_EQ(log.find("implicit", log.find("implicit") + 1), std::string::npos)
      << "logged more than once: " << log;

  hi::InterfaceManager manager;
  rt->registerInterfaces(manager);
  hi::JointHandle joint1 = manager.get<hi::EffortJointInterface>()->getHandle("joint1");
  joint1.setCommand(-4.0);
  rt->jointCommandToActuatorCommand();
  EXPECT_NEAR(rt->actuator(ActuatorIndex(0)).effort_command, -4.0, kTol);
}

TEST(RobotTransmissions, WithoutImplicitOptionUntransmittedJointsAreLeftOut) {
  EXPECT_EQ(fromUrdf(readSeed("minimal_robot_description.urdf"))->numJoints(), 0u);
  const auto seed = fromUrdf(readSeed("minimal_robot_description_w_jnt_ctl.urdf"), true);
  EXPECT_EQ(seed->numJoints(), 1u);
  EXPECT_TRUE(seed->implicitTransmissionJoints().empty());
}

TEST(RobotTransmissions, FiftyToOneScalesEffortAndMotion) {
  const auto rt = fromUrdf(kArm);
  const JointIndex shoulder = rt->jointIndex("shoulder");
  const ActuatorIndex motor = rt->actuatorIndex("shoulder_motor");

  rt->actuator(motor).effort = 0.2;      // N·m at the motor
  rt->actuator(motor).velocity = 100.0;  // rad/s at the motor
  rt->actuator(motor).position = 25.0;   // rad at the motor
  rt->actuatorStateToJointState();
  EXPECT_NEAR(rt->joint(shoulder).effort, 10.0, kTol);
  EXPECT_NEAR(rt->joint(shoulder).velocity, 2.0, kTol);
  EXPECT_NEAR(rt->joint(shoulder).position, 0.5, kTol);

  rt->joint(shoulder).effort_command = 10.0;
  rt->joint(shoulder).position_command = 0.1;
  rt->joint(shoulder).velocity_command = 7.0;  // not an interface of this joint
  rt->jointCommandToActuatorCommand();
  EXPECT_NEAR(rt->actuator(motor).effort_command, 0.2, kTol);
  EXPECT_NEAR(rt->actuator(motor).position_command, 5.0, kTol);
  EXPECT_EQ(rt->actuator(motor).velocity_command, 0.0);
}

TEST(RobotTransmissions, ReversedSimpleTransmissionWithOffsetMapsEveryDirection) {
  // n = -4 (the motor turns the other way), joint offset o = 0.3 rad:
  //   joint position = actuator position / n + o, joint velocity = actuator
  //   velocity / n, joint effort = n · actuator effort (by hand below).
  const char* urdf = R"(<?xml version="1.0"?>
<robot name="r">
  <link name="base"/><link name="arm"/>
  <joint name="j" type="continuous"><parent link="base"/><child link="arm"/></joint>
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><offset>0.3</offset>
      <hardwareInterface>EffortJointInterface</hardwareInterface>
      <hardwareInterface>VelocityJointInterface</hardwareInterface>
      <hardwareInterface>PositionJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>-4</mechanicalReduction></actuator>
  </transmission>
</robot>)";
  const auto rt = fromUrdf(urdf);
  const JointIndex j = rt->jointIndex("j");
  const ActuatorIndex m = rt->actuatorIndex("m");

  rt->actuator(m).position = 2.0;
  rt->actuator(m).velocity = -8.0;
  rt->actuator(m).effort = 0.5;
  rt->actuatorStateToJointState();
  EXPECT_NEAR(rt->joint(j).position, 2.0 / -4.0 + 0.3, kTol);  // -0.2
  EXPECT_NEAR(rt->joint(j).velocity, 2.0, kTol);
  EXPECT_NEAR(rt->joint(j).effort, -2.0, kTol);

  rt->joint(j).position = 1.3;
  rt->joint(j).velocity = 0.25;
  rt->joint(j).effort = 6.0;
  rt->jointStateToActuatorState();
  EXPECT_NEAR(rt->actuator(m).position, -4.0, kTol);  // -4 · (1.3 - 0.3)
  EXPECT_NEAR(rt->actuator(m).velocity, -1.0, kTol);
  EXPECT_NEAR(rt->actuator(m).effort, -1.5, kTol);

  rt->joint(j).effort_command = 6.0;
  rt->joint(j).velocity_command = 0.25;
  rt->joint(j).position_command = 1.3;
  rt->jointCommandToActuatorCommand();
  EXPECT_NEAR(rt->actuator(m).effort_command, -1.5, kTol);
  EXPECT_NEAR(rt->actuator(m).velocity_command, -1.0, kTol);
  EXPECT_NEAR(rt->actuator(m).position_command, -4.0, kTol);

  rt->actuator(m).effort_command = 0.5;
  rt->actuator(m).velocity_command = -8.0;
  rt->actuator(m).position_command = 2.0;
  rt->actuatorCommandToJointCommand();
  EXPECT_NEAR(rt->joint(j).effort_command, -2.0, kTol);
  EXPECT_NEAR(rt->joint(j).velocity_command, 2.0, kTol);
  EXPECT_NEAR(rt->joint(j).position_command, -0.2, kTol);
}

TEST(RobotTransmissions, ArmRegistersOnlyNamedCommandInterfaces) {
  const auto rt = fromUrdf(kArm);
  EXPECT_EQ(rt->numJoints(), 3u);
  EXPECT_EQ(rt->numActuators(), 3u);
  EXPECT_EQ(rt->numTransmissions(), 2u);
  EXPECT_FALSE(rt->hasJoint("passive"));
  hi::InterfaceManager manager;
  rt->registerInterfaces(manager);
  EXPECT_EQ(manager.get<hi::JointStateInterface>()->getNames(),
            (std::vector<std::string>{"pitch", "roll", "shoulder"}));
  EXPECT_EQ(manager.get<hi::EffortJointInterface>()->getNames(),
            std::vector<std::string>{"shoulder"});
  EXPECT_EQ(manager.get<hi::PositionJointInterface>()->getNames(),
            std::vector<std::string>{"shoulder"});
  EXPECT_EQ(manager.get<hi::VelocityJointInterface>()->getNames(),
            (std::vector<std::string>{"pitch", "roll"}));
  EXPECT_EQ(manager.get<hi::VelocityActuatorInterface>()->getNames(),
            (std::vector<std::string>{"wrist_left", "wrist_right"}));
  EXPECT_EQ(manager.get<hi::ActuatorStateInterface>()->getNames(),
            (std::vector<std::string>{"shoulder_motor", "wrist_left", "wrist_right"}));
}

// The capsule arm (tests/assets/xacro) in simulation declares a transmission
// per hardware interface of each arm joint, as franka_description does, and
// none has a <mechanicalReduction>: each joint offers every interface its
// transmissions name, and its actuator drives it 1:1.
TEST(RobotTransmissions, OneTransmissionPerInterfaceOffersEachInterfaceAtReductionOne) {
  std::ifstream file(std::string(SERVOLOOP_SOURCE_DIR) + "/tests/assets/xacro/capsule_arm_expanded.urdf");
  ASSERT_TRUE(file.good());
  std::stringstream text;
  text << file.rdbuf();
  const auto rt = fromUrdf(text.str());
  EXPECT_EQ(rt->numTransmissions(), 3u);
  hi::InterfaceManager manager;
  rt->registerInterfaces(manager);
  const std::vector<std::string> arm{"capsule_joint1", "capsule_joint2"};
  const std::vector<std::string> all{"capsule_finger_joint", "capsule_joint1", "capsule_joint2"};
  EXPECT_EQ(manager.get<hi::JointStateInterface>()->getNames(), all);
  EXPECT_EQ(manager.get<hi::EffortJointInterface>()->getNames(), all);
  EXPECT_EQ(manager.get<hi::PositionJointInterface>()->getNames(), arm);
  EXPECT_EQ(manager.get<hi::VelocityJointInterface>()->getNames(), arm);
  EXPECT_EQ(manager.get<hi::ActuatorStateInterface>()->getNames(),
            (std::vector<std::string>{"capsule_finger_joint_motor", "capsule_joint1_motor", "capsule_joint2_motor"}));

  const JointIndex j = rt->jointIndex("capsule_joint2");
  const ActuatorIndex m = rt->actuatorIndex("capsule_joint2_motor");
  rt->actuator(m).position = 0.7;
  rt->actuator(m).velocity = -0.3;
  rt->actuator(m).effort = 5.0;
  rt->actuatorStateToJointState();
  EXPECT_EQ(rt->joint(j).position, 0.7);
  EXPECT_EQ(rt->joint(j).velocity, -0.3);
  EXPECT_EQ(rt->joint(j).effort, 5.0);
}

TEST(RobotTransmissions, DifferentialWristMatchesReferenceCase) {
  const auto rt = fromUrdf(kArm);
  const JointIndex pitch = rt->jointIndex("pitch");
  const JointIndex roll = rt->jointIndex("roll");
  const ActuatorIndex left = rt->actuatorIndex("wrist_left");
  const ActuatorIndex right = rt->actuatorIndex("wrist_right");

  for (const ActuatorIndex a : {left, right}) {
    const double value = a == left ? 3.0 : 5.0;
    rt->actuator(a).position = rt->actuator(a).velocity = rt->actuator(a).effort = value;
  }
  rt->actuatorStateToJointState();
  EXPECT_NEAR(rt->joint(pitch).effort, 140.0, kTol);
  EXPECT_NEAR(rt->joint(roll).effort, 520.0, kTol);
  EXPECT_NEAR(rt->joint(pitch).velocity, -0.0125, kTol);
  EXPECT_NEAR(rt->joint(roll).velocity, 0.06875, kTol);
  EXPECT_NEAR(rt->joint(pitch).position, -2.0125, kTol);
  EXPECT_NEAR(rt->joint(roll).position, 4.06875, kTol);

  // Write path with the velocity interface the URDF names.
  rt->joint(pitch).velocity_command = -0.0125;
  rt->joint(roll).velocity_command = 0.06875;
  rt->jointCommandToActuatorCommand();
  EXPECT_NEAR(rt->actuator(left).velocity_command, 3.0, kTol);
  EXPECT_NEAR(rt->actuator(right).velocity_command, 5.0, kTol);
  EXPECT_EQ(rt->actuator(left).effort_command, 0.0);
}

TEST(RobotTransmissions, SimulationDirections) {
  const auto rt = fromUrdf(kArm);
  const JointIndex shoulder = rt->jointIndex("shoulder");
  const JointIndex pitch = rt->jointIndex("pitch");
  const JointIndex roll = rt->jointIndex("roll");
  const ActuatorIndex motor = rt->actuatorIndex("shoulder_motor");
  const ActuatorIndex left = rt->actuatorIndex("wrist_left");
  const ActuatorIndex right = rt->actuatorIndex("wrist_right");

  // A simulator measures the joints; the actuator state follows the inverse map.
  rt->joint(shoulder).position = 0.5;
  rt->joint(shoulder).velocity = 2.0;
  rt->joint(shoulder).effort = 10.0;
  rt->joint(pitch).position = -2.0125;
  rt->joint(roll).position = 4.06875;
  rt->joint(pitch).effort = 140.0;
  rt->joint(roll).effort = 520.0;
  rt->jointStateToActuatorState();
  EXPECT_NEAR(rt->actuator(motor).position, 25.0, kTol);
  EXPECT_NEAR(rt->actuator(motor).velocity, 100.0, kTol);
  EXPECT_NEAR(rt->actuator(motor).effort, 0.2, kTol);
  EXPECT_NEAR(rt->actuator(left).position, 3.0, kTol);
  EXPECT_NEAR(rt->actuator(right).position, 5.0, kTol);
  EXPECT_NEAR(rt->actuator(left).effort, 3.0, kTol);
  EXPECT_NEAR(rt->actuator(right).effort, 5.0, kTol);

  // Actuator commands become what the simulator applies to its joints.
  rt->actuator(motor).effort_command = 0.2;
  rt->actuator(left).effort_command = 3.0;
  rt->actuator(right).effort_command = 5.0;
  rt->actuatorEffortToJointEffort();
  EXPECT_NEAR(rt->joint(shoulder).effort_command, 10.0, kTol);
  EXPECT_NEAR(rt->joint(pitch).effort_command, 140.0, kTol);
  EXPECT_NEAR(rt->joint(roll).effort_command, 520.0, kTol);

  rt->actuator(left).velocity_command = 3.0;
  rt->actuator(right).velocity_command = 5.0;
  rt->actuatorVelocityToJointVelocity();
  EXPECT_NEAR(rt->joint(pitch).velocity_command, -0.0125, kTol);
  EXPECT_NEAR(rt->joint(roll).velocity_command, 0.06875, kTol);

  rt->actuator(motor).position_command = 5.0;
  rt->actuatorPositionToJointPosition();
  EXPECT_NEAR(rt->joint(shoulder).position_command, 0.1, kTol);

  // The per-interface variant leaves interfaces a joint does not name alone.
  rt->joint(pitch).position_command = 123.0;
  rt->actuator(left).position_command = 1.0;
  rt->actuatorCommandToJointCommand();
  EXPECT_EQ(rt->joint(pitch).position_command, 123.0);
}

TEST(RobotTransmissions, LookupErrorsNameTheJointOrActuator) {
  const auto rt = fromUrdf(kArm);
  try {
    rt->jointIndex("passive");
    FAIL() << "expected servoloop::ConfigError";
  } catch (const servoloop::ConfigError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("joint 'passive'"), std::string::npos) << message;
    EXPECT_NE(message.find("shoulder"), std::string::npos) << message;
  }
  try {
    rt->actuatorIndex("elbow_motor");
    FAIL() << "expected servoloop::ConfigError";
  } catch (const servoloop::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("actuator 'elbow_motor'"), std::string::npos);
  }
}

TEST(RobotTransmissions, RejectsInfoForJointTheRobotLacks) {
  st::TransmissionInfo info;
  info.name = "ghost_trans";
  info.type = st::kSimpleTransmissionType;
  info.joints.push_back({"ghost", {"EffortJointInterface"}, "", 1.0, 0.0});
  info.actuators.push_back({"ghost_motor", {}, "", 1.0});
  urdf::ModelInterface robot;
  robot.name_ = "empty";
  st::RobotTransmissionsOptions options;
  options.source_name = "empty.urdf";
  try {
    st::RobotTransmissions rt(robot, {info}, options);
    FAIL() << "expected servoloop::ConfigError";
  } catch (const servoloop::ConfigError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("empty.urdf: transmission 'ghost_trans': joint 'ghost'"),
              std::string::npos)
        << message;
  }
}

TEST(RobotTransmissions, RejectsImplicitActuatorNameClash) {
  // "a" has a transmission whose actuator is called "b_motor": the implicit
  // actuator of "b" would collide with it.
  const std::string xml = R"(<robot name="clash">
  <link name="l0"/><link name="l1"/><link name="l2"/>
  <joint name="a" type="continuous"><parent link="l0"/><child link="l1"/></joint>
  <joint name="b" type="continuous"><parent link="l1"/><child link="l2"/></joint>
  <transmission name="ta"><type>transmission_interface/SimpleTransmission</type>
    <joint name="a"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="b_motor"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission></robot>)";
  try {
    fromUrdf(xml, /*implicit=*/true);
    FAIL() << "expected servoloop::ConfigError";
  } catch (const servoloop::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("actuator 'b_motor' is already used"), std::string::npos)
        << e.what();
  }
}
