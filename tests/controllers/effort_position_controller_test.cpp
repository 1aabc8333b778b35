// effort_controllers/JointPositionController against hand calculations of
// control_toolbox's PID and ros_control's setpoint and error rules.
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "controller_test_support.hpp"
#include "servoloop/controllers/effort_controllers/joint_position_controller.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/params/parameters_yaml.hpp"

namespace servoloop::controllers {
namespace {

using effort_controllers::JointPositionController;
using testing::initController;
using testing::makeContext;
using testing::TestJointsHW;
using StateMsg = servoloop::control_msgs::JointControllerState;
using Float64 = servoloop::std_msgs::Float64;


class EffortPositionTest : public ::testing::Test {
 protected:
  // A P-only controller (p = 1, no i, no d) on one joint of the test robot:
  // its effort equals the position error.
  void initProportional(const std::string& joint) {
    initController(controller, hw,
                   makeContext("pos", "{joint: " + joint + ", pid: {p: 1.0}}", &bus,
                               testing::testRobotModel()));
  }
  double effortOf(const std::string& joint) { return hw.effort_command[hw.index(joint)]; }
  void command(double value) { bus.publish("/robot/pos/command", Float64{value}); }

  servoloop::realtime::TopicBus bus;
  TestJointsHW hw{{"rev", "cont", "slide", "wide"}};
  JointPositionController controller;
};

TEST(EffortPositionSeed, OneUpdateOfTheSeedControllerMatchesControlToolbox) {
  // The seed's robot and YAML: joint1 revolute in [0, 2], pid p 10 i 10 d 10 i_clamp ±10.
  servoloop::realtime::TopicBus bus;
  TestJointsHW hw({"joint1"});
  controller_manager::ControllerContext context;
  context.name = "joint1_position_controller";
  context.robot_namespace = "/one_DOF_robot";
  context.params = servoloop::params::parametersFromYaml(
      testing::seedControllerParams()["joint1_position_controller"], "/one_DOF_robot/joint1_position_controller");
  context.topics = &bus;
  context.robot_model = testing::seedRobotModel();
  JointPositionController controller;
  initController(controller, hw, context);

  hw.position[0] = 0.5;
  controller.startRequest(Time(0.0));
  EXPECT_DOUBLE_EQ(controller.setpoint(), 0.5);  // starts where the joint is
  bus.publish("/one_DOF_robot/joint1_position_controller/command", Float64{1.0});

  const double kp = 10.0, ki = 10.0, kd = 10.0, i_clamp = 10.0, dt = 0.001;
  const double error = 1.0 - 0.5;
  // control_toolbox: P + clamp(I) + D, the derivative taken from a previous error of 0.
  const double integral = dt * error;
  const double expected_first = kp * error + std::clamp(ki * integral, -i_clamp, i_clamp) +
                                kd * (error - 0.0) / dt;
  ASSERT_EQ(controller.update(Time(dt), Duration(dt)), ReturnType::ok);
  EXPECT_NEAR(hw.effort_command[0], expected_first, 1e-9);
  EXPECT_NEAR(hw.effort_command[0], 5005.005, 1e-9);

  // Second update, joint not moved: the integral doubles, the derivative is 0.
  const double expected_second = kp * error + std::clamp(ki * 2.0 * integral, -i_clamp, i_clamp);
  ASSERT_EQ(controller.update(Time(2 * dt), Duration(dt)), ReturnType::ok);
  EXPECT_NEAR(hw.effort_command[0], expected_second, 1e-9);
}

TEST_F(EffortPositionTest, RevoluteSetpointIsClampedToTheUrdfLimits) {
  initProportional("rev");  // limits [0, 2]
  hw.position[hw.index("rev")] = 1.0;
  controller.startRequest(Time(0.0));
  command(3.0);
  controller.update(Time(0.001), Duration(0.001));
  EXPECT_DOUBLE_EQ(controller.setpoint(), 2.0);
  EXPECT_NEAR(effortOf("rev"), 1.0, 1e-12);  // 2 - 1
  command(-1.0);
  controller.update(Time(0.002), Duration(0.001));
  EXPECT_DOUBLE_EQ(controller.setpoint(), 0.0);
  EXPECT_NEAR(effortOf("rev"), -1.0, 1e-12);
}

TEST_F(EffortPositionTest, ContinuousJointTakesTheShortWayRound) {
  initProportional("cont");
  hw.position[hw.index("cont")] = -3.0;
  controller.startRequest(Time(0.0));
  command(3.0);
  controller.update(Time(0.001), Duration(0.001));
  EXPECT_DOUBLE_EQ(controller.setpoint(), 3.0);  // no clamping
  // From -3 to 3 through ±π: 6 - 2π (about -0.283), not +6.
  EXPECT_NEAR(effortOf("cont"), 6.0 - 2.0 * std::numbers::pi, 1e-12);

  hw.position[hw.index("cont")] = 3.0;
  command(-3.0);
  controller.update(Time(0.002), Duration(0.001));
  EXPECT_NEAR(effortOf("cont"), 2.0 * std::numbers::pi - 6.0, 1e-12);
}

TEST_F(EffortPositionTest, PrismaticJointUsesTheDifferenceWithinItsLimits) {
  initProportional("slide");  // limits [-0.5, 0.5]
  hw.position[hw.index("slide")] = -0.25;
  controller.startRequest(Time(0.0));
  command(0.4);
  controller.update(Time(0.001), Duration(0.001));
  EXPECT_NEAR(effortOf("slide"), 0.65, 1e-12);
  command(7.0);
  controller.update(Time(0.002), Duration(0.001));
  EXPECT_NEAR(effortOf("slide"), 0.75, 1e-12);  // setpoint clamped to 0.5
}

TEST_F(EffortPositionTest, RevoluteWiderThanATurnMayWrapInsideItsLimits) {
  initProportional("wide");  // limits [-4, 4]
  hw.position[hw.index("wide")] = 3.0;
  controller.startRequest(Time(0.0));
  command(-3.0);  // also reachable as -3 + 2π = 3.283 inside the limits
  controller.update(Time(0.001), Duration(0.001));
  EXPECT_NEAR(effortOf("wide"), 2.0 * std::numbers::pi - 6.0, 1e-12);
}

TEST_F(EffortPositionTest, StartingHoldsTheCurrentPositionAndResetsThePid) {
  initController(controller, hw,
                 makeContext("pos", "{joint: rev, pid: {p: 2.0, i: 1.0, d: 0.5, i_clamp: 100}}", &bus,
                             testing::testRobotModel()));
  hw.position[hw.index("rev")] = 1.2;
  controller.startRequest(Time(0.0));
  controller.update(Time(0.001), Duration(0.001));
  EXPECT_DOUBLE_EQ(controller.setpoint(), 1.2);
  EXPECT_DOUBLE_EQ(effortOf("rev"), 0.0);

  // Build up integral and previous error, then restart elsewhere: no memory of it.
  command(1.7);
  for (int k = 2; k <= 20; ++k) controller.update(Time(0.001 * k), Duration(0.001));
  EXPECT_NE(effortOf("rev"), 0.0);
  controller.stopRequest(Time(0.020));
  hw.position[hw.index("rev")] = 0.3;
  controller.startRequest(Time(0.030));
  controller.update(Time(0.031), Duration(0.001));
  EXPECT_DOUBLE_EQ(controller.setpoint(), 0.3);  // the old command 1.7 is forgotten
  EXPECT_DOUBLE_EQ(effortOf("rev"), 0.0);
}

TEST_F(EffortPositionTest, StateTopicEveryTenthUpdate) {
  initController(controller, hw,
                 makeContext("pos", "{joint: rev, pid: {p: 3.0, i: 2.0, d: 0.0, i_clamp: 4.0}}", &bus,
                             testing::testRobotModel()));
  std::vector<StateMsg> states;
  auto subscription = bus.subscribe<StateMsg>("/robot/pos/state",
                                              [&](const StateMsg& msg) { states.push_back(msg); });
  hw.position[hw.index("rev")] = 0.5;
  hw.velocity[hw.index("rev")] = 0.125;
  controller.startRequest(Time(0.0));
  command(1.5);
  for (int k = 1; k <= 25; ++k) controller.update(Time(0.002 * k), Duration(0.002));
  bus.flush();
  ASSERT_EQ(states.size(), 3u);  // updates 1, 11 and 21

  const StateMsg& first = states[0];
  EXPECT_DOUBLE_EQ(first.stamp, 0.002);
  EXPECT_DOUBLE_EQ(first.set_point, 1.5);
  EXPECT_DOUBLE_EQ(first.process_value, 0.5);
  EXPECT_DOUBLE_EQ(first.process_value_dot, 0.125);
  EXPECT_DOUBLE_EQ(first.error, 1.0);
  EXPECT_DOUBLE_EQ(first.time_step, 0.002);
  EXPECT_NEAR(first.command, 3.0 * 1.0 + 2.0 * (0.002 * 1.0), 1e-12);
  EXPECT_DOUBLE_EQ(first.p, 3.0);
  EXPECT_DOUBLE_EQ(first.i, 2.0);
  EXPECT_DOUBLE_EQ(first.d, 0.0);
  EXPECT_DOUBLE_EQ(first.i_clamp, 4.0);
  // Update 11: the integral holds 11 steps of error 1.
  EXPECT_DOUBLE_EQ(states[1].stamp, 0.022);
  EXPECT_NEAR(states[1].command, 3.0 + 2.0 * (11 * 0.002), 1e-12);
}

TEST_F(EffortPositionTest, NonFiniteCommandsAreIgnoredAndCounted) {
  initProportional("rev");
  hw.position[hw.index("rev")] = 0.0;
  controller.startRequest(Time(0.0));
  command(1.5);
  controller.update(Time(0.001), Duration(0.001));
  EXPECT_DOUBLE_EQ(controller.setpoint(), 1.5);
  command(std::numeric_limits<double>::quiet_NaN());
  controller.update(Time(0.002), Duration(0.001));
  command(std::numeric_limits<double>::infinity());
  controller.update(Time(0.003), Duration(0.001));
  controller.update(Time(0.004), Duration(0.001));  // the same bad value is counted once
  EXPECT_DOUBLE_EQ(controller.setpoint(), 1.5);
  EXPECT_DOUBLE_EQ(effortOf("rev"), 1.5);
  EXPECT_EQ(controller.rejectedNonFiniteCommands(), 2u);
}

TEST_F(EffortPositionTest, VelocityTargetFeedsTheDerivativeTerm) {
  initController(controller, hw,
                 makeContext("pos", "{joint: rev, pid: {p: 1.0, d: 2.0}}", &bus, testing::testRobotModel()));
  hw.position[hw.index("rev")] = 1.0;
  hw.velocity[hw.index("rev")] = 0.25;
  controller.startRequest(Time(0.0));
  controller.setCommand(1.5, 0.75);
  controller.update(Time(0.001), Duration(0.001));
  // PID(e, v_cmd - v, dt) = p·0.5 + d·(0.75 - 0.25): no derivative kick.
  EXPECT_NEAR(effortOf("rev"), 1.0 * 0.5 + 2.0 * 0.5, 1e-12);
}

TEST_F(EffortPositionTest, ParameterErrorsNameTheKey) {
  std::vector<hardware_interface::InterfaceResources> claimed;
  const auto expectError = [&](const std::string& params, const std::string& fragment) {
    JointPositionController fresh;
    try {
      fresh.initRequest(&hw, makeContext("pos", params, &bus, testing::testRobotModel()), claimed);
      ADD_FAILURE() << "expected ConfigError for " << params;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  expectError("{pid: {p: 1}}", "robot/pos/joint");
  expectError("{joint: rev}", "No p gain specified");
  expectError("{joint: rev, pid: {i: 1}}", "robot/pos/pid");
  expectError("{joint: nowhere, pid: {p: 1}}", "'nowhere'");
}

TEST_F(EffortPositionTest, ClaimsItsJointOnTheEffortInterface) {
  std::vector<hardware_interface::InterfaceResources> claimed;
  ASSERT_TRUE(controller.initRequest(
      &hw, makeContext("pos", "{joint: slide, pid: {p: 1}}", &bus, testing::testRobotModel()), claimed));
  ASSERT_EQ(claimed.size(), 1u);
  EXPECT_EQ(claimed[0].hardware_interface, "EffortJointInterface");
  EXPECT_EQ(claimed[0].resources, (std::set<std::string>{"slide"}));
}

}  // namespace
}  // namespace servoloop::controllers
