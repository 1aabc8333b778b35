// Parsing of <ns>/sim and <ns>/actuators: defaults, values, and errors that
// name the key and say what it must be.
#include <cmath>
#include <functional>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "thrown_message.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/sim_common/sim_settings.hpp"
#include "sim_test_support.hpp"

namespace servoloop::sim_common {
namespace {

using servoloop::testing::thrownMessage;

using ::testing::HasSubstr;

class SimSettingsTest : public ::testing::Test {
 protected:
  SimSettings parse(const std::string& yaml) {
    return parseSimSettings(YAML::Load(yaml), *model_, "/robot");
  }
  std::string errorOf(const std::string& yaml) {
    return thrownMessage<ConfigError>([&] { parse(yaml); });
  }

  std::shared_ptr<const urdf::ModelInterface> model_ = parseRobotModel(
      sim_testing::armUrdf(1.0, sim_testing::kEffortInterface, "revolute",
                           R"(<limit lower="-1" upper="1" effort="10" velocity="1"/>)"),
      "arm.urdf");
};

TEST_F(SimSettingsTest, DefaultsWithoutASimKey) {
  for (const SimSettings& settings : {parse("{}"), parseSimSettings(YAML::Node(), *model_, "/robot")}) {
    EXPECT_DOUBLE_EQ(settings.time_step_s, 0.001);
    EXPECT_EQ(settings.gravity, Eigen::Vector3d(0.0, 0.0, -9.81));
    EXPECT_FALSE(settings.ground_plane);
    EXPECT_TRUE(settings.initial_positions.empty());
  }
}

TEST_F(SimSettingsTest, ReadsEveryKey) {
  const SimSettings settings = parse(R"(
sim:
  time_step: 0.0005
  gravity: [1, 2, 3]
  ground_plane: true
  initial_positions: {arm_joint: -0.5}
  not_a_key: 3  # warned and ignored
)");
  EXPECT_DOUBLE_EQ(settings.time_step_s, 0.0005);
  EXPECT_EQ(settings.gravity, Eigen::Vector3d(1.0, 2.0, 3.0));
  EXPECT_TRUE(settings.ground_plane);
  EXPECT_DOUBLE_EQ(settings.initial_positions.at("arm_joint"), -0.5);
}

TEST_F(SimSettingsTest, BadValuesNameTheirKey) {
  EXPECT_THAT(errorOf("sim: {time_step: abc}"),
              HasSubstr("/robot/sim/time_step: expected a number, got 'abc'"));
  EXPECT_THAT(errorOf("sim: {time_step: -0.001}"),
              HasSubstr("/robot/sim/time_step: expected a number from 1e-06 to 1, got '-0.001'"));
  EXPECT_THAT(errorOf("sim: {time_step: 1e-12}"), HasSubstr("/robot/sim/time_step: expected a number from 1e-06 to 1, got '1e-12'"));
  EXPECT_THAT(errorOf("sim: {gravity: [0, 1]}"),
              HasSubstr("/robot/sim/gravity: expected a list of 3 numbers"));
  EXPECT_THAT(errorOf("sim: {gravity: [0, x, 1]}"), HasSubstr("/robot/sim/gravity[1]: expected a number"));
  EXPECT_THAT(errorOf("sim: {ground_plane: maybe}"),
              HasSubstr("/robot/sim/ground_plane: expected a boolean (true or false), got 'maybe'"));
  EXPECT_THAT(errorOf("sim: [1, 2]"), HasSubstr("/robot/sim: expected a map"));
}

TEST_F(SimSettingsTest, InitialPositionsMustNameAMovableJointInsideItsLimits) {
  const std::string unknown = errorOf("sim: {initial_positions: {elbow: 0.1}}");
  EXPECT_THAT(unknown, HasSubstr("/robot/sim/initial_positions/elbow"));
  EXPECT_THAT(unknown, HasSubstr("movable joints: arm_joint"));
  EXPECT_THAT(errorOf("sim: {initial_positions: {arm_joint: 1.5}}"),
              HasSubstr("/robot/sim/initial_positions/arm_joint: 1.500000 lies outside the joint's URDF "
                        "position limits [-1.000000, 1.000000]"));
  EXPECT_THAT(errorOf("sim: {initial_positions: {arm_joint: up}}"),
              HasSubstr("/robot/sim/initial_positions/arm_joint: expected a number, got 'up'"));
}

TEST_F(SimSettingsTest, BaseAndSelfCollisionDefaultToGazebos) {
  const SimSettings settings = parse("{}");
  EXPECT_EQ(settings.base, BaseMode::automatic);
  EXPECT_FALSE(settings.self_collide);
  EXPECT_EQ(settings.base_position, Eigen::Vector3d::Zero());
  EXPECT_TRUE(settings.base_orientation.isApprox(Eigen::Quaterniond::Identity()));
  // The URDF's <gazebo><self_collide> is the default a parameter overrides.
  EXPECT_TRUE(parseSimSettings(YAML::Load("{}"), *model_, "/robot", true).self_collide);
  EXPECT_FALSE(parseSimSettings(YAML::Load("{sim: {self_collide: false}}"), *model_, "/robot", true).self_collide);
}

TEST_F(SimSettingsTest, ReadsFixedBaseAndThePoseAsUrdfRpy) {
  const SimSettings settings = parse("{sim: {fixed_base: true, self_collide: true, pose: [1, 2, 3, 0.1, 0.2, 0.3]}}");
  EXPECT_EQ(settings.base, BaseMode::fixed);
  EXPECT_TRUE(settings.self_collide);
  EXPECT_EQ(settings.base_position, Eigen::Vector3d(1, 2, 3));
  // URDF rpy: R = Rz(yaw) Ry(pitch) Rx(roll); its first column, worked by hand:
  // (cos y cos p, sin y cos p, −sin p).
  const Eigen::Matrix3d r = settings.base_orientation.toRotationMatrix();
  EXPECT_NEAR(r(0, 0), std::cos(0.3) * std::cos(0.2), 1e-15);
  EXPECT_NEAR(r(1, 0), std::sin(0.3) * std::cos(0.2), 1e-15);
  EXPECT_NEAR(r(2, 0), -std::sin(0.2), 1e-15);
  // and its last row: (−sin p, cos p sin r, cos p cos r).
  EXPECT_NEAR(r(2, 1), std::cos(0.2) * std::sin(0.1), 1e-15);
  EXPECT_NEAR(r(2, 2), std::cos(0.2) * std::cos(0.1), 1e-15);

  EXPECT_EQ(parse("{sim: {fixed_base: false}}").base, BaseMode::floating);
  EXPECT_EQ(parse("{sim: {pose: [0, 0, 0.5]}}").base_position, Eigen::Vector3d(0, 0, 0.5));
}

TEST_F(SimSettingsTest, BadBaseValuesNameTheirKey) {
  EXPECT_THAT(errorOf("{sim: {pose: [1, 2]}}"), HasSubstr("/robot/sim/pose: expected [x, y, z] or [x, y, z, roll"));
  EXPECT_THAT(errorOf("{sim: {pose: [1, 2, .nan]}}"), HasSubstr("/robot/sim/pose[2]"));
  EXPECT_THAT(errorOf("{sim: {fixed_base: maybe}}"), HasSubstr("/robot/sim/fixed_base: expected a boolean"));
  EXPECT_THAT(errorOf("{sim: {self_collide: 3}}"), HasSubstr("/robot/sim/self_collide: expected a boolean"));
}

TEST(SimSettingsUrdf, SelfCollisionIsTheModelsGazeboTagOnly) {
  EXPECT_FALSE(urdfRequestsSelfCollision("<robot name='r'><link name='a'/></robot>"));
  EXPECT_TRUE(urdfRequestsSelfCollision(
      "<robot name='r'><link name='a'/><gazebo><self_collide>true</self_collide></gazebo></robot>"));
  EXPECT_TRUE(urdfRequestsSelfCollision(
      "<robot name='r'><link name='a'/><gazebo><self_collide> 1 </self_collide></gazebo></robot>"));
  // A link's <gazebo reference=...> settings are not the model's.
  EXPECT_FALSE(urdfRequestsSelfCollision(
      "<robot name='r'><link name='a'/><gazebo reference='a'><self_collide>true</self_collide></gazebo></robot>"));
  EXPECT_FALSE(urdfRequestsSelfCollision(
      "<robot name='r'><link name='a'/><gazebo><self_collide>false</self_collide></gazebo></robot>"));
  EXPECT_FALSE(urdfRequestsSelfCollision("not xml"));
}

// The base is fixed by a root named world, or by a root body without mass —
// the root link and what is fixed to it, lumped as Gazebo does: a massless
// base_footprint carrying a heavy base_link floats.
TEST(SimSettingsUrdf, FixedBaseFollowsTheRootBodysMass) {
  const std::string inertial =
      R"(<inertial><mass value="3"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>)";
  const auto model = [&](const std::string& root_inertial, const std::string& fixed_child_inertial) {
    return parseRobotModel(R"(<robot name="r"><link name="base_footprint">)" + root_inertial +
                               R"(</link><link name="base_link">)" + fixed_child_inertial +
                               R"(</link><joint name="f" type="fixed"><parent link="base_footprint"/>
                               <child link="base_link"/></joint></robot>)",
                           "r.urdf");
  };
  EXPECT_FALSE(isFixedBase(*model("", inertial), BaseMode::automatic));
  EXPECT_FALSE(isFixedBase(*model(inertial, ""), BaseMode::automatic));
  EXPECT_TRUE(isFixedBase(*model("", ""), BaseMode::automatic));
  EXPECT_TRUE(isFixedBase(*model(inertial, inertial), BaseMode::fixed));
  EXPECT_FALSE(isFixedBase(*model("", ""), BaseMode::floating));
  EXPECT_DOUBLE_EQ(rigidBodyMass(*model(inertial, inertial)->getRoot()), 6.0);
}

TEST(ActuatorParametersTest, DefaultsAndValues) {
  const auto parameters = parseActuatorParameters(
      YAML::Load("actuators: {motor1: {max_effort: 0.2, rotor_inertia: 1.0e-4}}"), {"motor1", "motor2"},
      "/robot");
  EXPECT_DOUBLE_EQ(parameters.at("motor1").max_effort, 0.2);
  EXPECT_DOUBLE_EQ(parameters.at("motor1").rotor_inertia, 1.0e-4);
  EXPECT_TRUE(std::isinf(parameters.at("motor2").max_effort));
  EXPECT_DOUBLE_EQ(parameters.at("motor2").rotor_inertia, 0.0);
}

TEST(ActuatorParametersTest, ErrorsNameTheActuatorAndKey) {
  const auto errorOf = [](const std::string& yaml) {
    return thrownMessage<ConfigError>([&] { parseActuatorParameters(YAML::Load(yaml), {"motor1"}, "/robot"); });
  };
  const std::string unknown = errorOf("actuators: {motor9: {max_effort: 1}}");
  EXPECT_THAT(unknown, HasSubstr("/robot/actuators/motor9: the robot has no actuator 'motor9' (actuators: motor1"));
  EXPECT_THAT(errorOf("actuators: {motor1: {max_effort: -1}}"),
              HasSubstr("/robot/actuators/motor1/max_effort: expected a number > 0, got '-1'"));
  EXPECT_THAT(errorOf("actuators: {motor1: {rotor_inertia: heavy}}"),
              HasSubstr("/robot/actuators/motor1/rotor_inertia: expected a number, got 'heavy'"));
  EXPECT_THAT(errorOf("actuators: {motor1: 3}"), HasSubstr("/robot/actuators/motor1: expected a map"));
}

}  // namespace
}  // namespace servoloop::sim_common
