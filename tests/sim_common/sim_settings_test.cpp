// Parsing of <ns>/sim and <ns>/actuators: defaults, values, and errors that
// name the key and say what it must be.
#include <cmath>
#include <functional>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/robot_model.hpp"
#include "servoloop/sim_common/sim_settings.hpp"
#include "sim_test_support.hpp"

namespace servoloop::sim_common {
namespace {

using ::testing::HasSubstr;

std::string configErrorOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const ConfigError& error) {
    return error.what();
  }
  ADD_FAILURE() << "expected servoloop::ConfigError";
  return "";
}

class SimSettingsTest : public ::testing::Test {
 protected:
  SimSettings parse(const std::string& yaml) {
    return parseSimSettings(YAML::Load(yaml), *model_, "/robot");
  }
  std::string errorOf(const std::string& yaml) {
    return configErrorOf([&] { parse(yaml); });
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
  EXPECT_THAT(errorOf("sim: {time_step: -0.001}"), HasSubstr("/robot/sim/time_step: expected a time step > 0"));
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
    return configErrorOf([&] { parseActuatorParameters(YAML::Load(yaml), {"motor1"}, "/robot"); });
  };
  const std::string unknown = errorOf("actuators: {motor9: {max_effort: 1}}");
  EXPECT_THAT(unknown, HasSubstr("/robot/actuators/motor9: the robot has no actuator 'motor9' (actuators: motor1"));
  EXPECT_THAT(errorOf("actuators: {motor1: {max_effort: -1}}"),
              HasSubstr("/robot/actuators/motor1/max_effort: expected a motor effort limit > 0"));
  EXPECT_THAT(errorOf("actuators: {motor1: {rotor_inertia: heavy}}"),
              HasSubstr("/robot/actuators/motor1/rotor_inertia: expected a number, got 'heavy'"));
  EXPECT_THAT(errorOf("actuators: {motor1: 3}"), HasSubstr("/robot/actuators/motor1: expected a map"));
}

}  // namespace
}  // namespace servoloop::sim_common
