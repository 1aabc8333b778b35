// The forward-command controllers of effort_controllers, position_controllers
// and velocity_controllers, single joint and group.
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "controller_test_support.hpp"
#include "servoloop/controllers/effort_controllers/forward_controllers.hpp"
#include "servoloop/controllers/position_controllers/forward_controllers.hpp"
#include "servoloop/controllers/velocity_controllers/forward_controllers.hpp"

namespace servoloop::controllers {
namespace {

using testing::initController;
using testing::makeContext;
using testing::TestJointsHW;
using Float64 = servoloop::std_msgs::Float64;
using Float64MultiArray = servoloop::std_msgs::Float64MultiArray;

class ForwardTest : public ::testing::Test {
 protected:
  servoloop::realtime::TopicBus bus;
  TestJointsHW hw{{"a", "b", "c"}};
};

TEST_F(ForwardTest, EffortControllerWritesTheLastCommandEveryCycle) {
  effort_controllers::JointEffortController controller;
  initController(controller, hw, makeContext("eff", "{joint: b}", &bus));
  hw.effort_command[1] = 42.0;
  controller.startRequest(Time(0.0));
  controller.update(Time(0.001), Duration(0.001));
  EXPECT_DOUBLE_EQ(hw.effort_command[1], 0.0);  // starts at 0

  bus.publish("/robot/eff/command", Float64{-3.5});
  for (int k = 2; k <= 4; ++k) {
    hw.effort_command[1] = 99.0;  // anything written in between is overwritten
    controller.update(Time(0.001 * k), Duration(0.001));
    EXPECT_DOUBLE_EQ(hw.effort_command[1], -3.5);
  }
  bus.publish("/robot/eff/command", Float64{std::numeric_limits<double>::infinity()});
  controller.update(Time(0.005), Duration(0.001));
  EXPECT_DOUBLE_EQ(hw.effort_command[1], -3.5);
  EXPECT_EQ(controller.rejectedNonFiniteCommands(), 1u);
  EXPECT_DOUBLE_EQ(hw.effort_command[0], 0.0);  // other joints untouched
}

TEST_F(ForwardTest, PositionControllerStartsAtTheCurrentPosition) {
  position_controllers::JointPositionController controller;
  initController(controller, hw, makeContext("pos", "{joint: a}", &bus));
  hw.position[0] = 0.75;
  controller.startRequest(Time(0.0));
  controller.update(Time(0.001), Duration(0.001));
  EXPECT_DOUBLE_EQ(hw.position_command[0], 0.75);
  bus.publish("/robot/pos/command", Float64{1.25});
  controller.update(Time(0.002), Duration(0.001));
  EXPECT_DOUBLE_EQ(hw.position_command[0], 1.25);
}

TEST_F(ForwardTest, VelocityControllerStartsAtZero) {
  velocity_controllers::JointVelocityController controller;
  initController(controller, hw, makeContext("vel", "{joint: c}", &bus));
  hw.velocity_command[2] = 5.0;
  controller.startRequest(Time(0.0));
  controller.update(Time(0.001), Duration(0.001));
  EXPECT_DOUBLE_EQ(hw.velocity_command[2], 0.0);
  bus.publish("/robot/vel/command", Float64{-0.5});
  controller.update(Time(0.002), Duration(0.001));
  EXPECT_DOUBLE_EQ(hw.velocity_command[2], -0.5);
}

TEST_F(ForwardTest, GroupEffortIgnoresCommandsOfTheWrongSize) {
  effort_controllers::JointGroupEffortController controller;
  initController(controller, hw, makeContext("group", "{joints: [c, a]}", &bus));
  controller.startRequest(Time(0.0));
  bus.publish("/robot/group/command", Float64MultiArray{{1.0, 2.0}});
  controller.update(Time(0.001), Duration(0.001));
  EXPECT_DOUBLE_EQ(hw.effort_command[2], 1.0);  // `joints` order: c, then a
  EXPECT_DOUBLE_EQ(hw.effort_command[0], 2.0);

  bus.publish("/robot/group/command", Float64MultiArray{{7.0, 8.0, 9.0}});
  controller.update(Time(0.002), Duration(0.001));
  bus.publish("/robot/group/command", Float64MultiArray{{7.0}});
  controller.update(Time(0.003), Duration(0.001));
  bus.publish("/robot/group/command", Float64MultiArray{{7.0, std::numeric_limits<double>::quiet_NaN()}});
  controller.update(Time(0.004), Duration(0.001));
  EXPECT_DOUBLE_EQ(hw.effort_command[2], 1.0);
  EXPECT_DOUBLE_EQ(hw.effort_command[0], 2.0);
  EXPECT_EQ(controller.rejectedWrongSizeCommands(), 2u);
  EXPECT_EQ(controller.rejectedNonFiniteCommands(), 1u);
  bus.flush();  // the delivery-side check logs the first of each (not asserted here)
}

TEST_F(ForwardTest, GroupPositionHoldsAndGroupVelocityStartsAtZero) {
  position_controllers::JointGroupPositionController positions;
  velocity_controllers::JointGroupVelocityController velocities;
  initController(positions, hw, makeContext("gpos", "{joints: [a, b]}", &bus));
  initController(velocities, hw, makeContext("gvel", "{joints: [c]}", &bus));
  hw.position[0] = 0.1;
  hw.position[1] = 0.2;
  hw.position[2] = 0.3;
  hw.velocity_command[2] = 4.0;
  positions.startRequest(Time(0.0));
  velocities.startRequest(Time(0.0));
  positions.update(Time(0.001), Duration(0.001));
  velocities.update(Time(0.001), Duration(0.001));
  EXPECT_DOUBLE_EQ(hw.position_command[0], 0.1);
  EXPECT_DOUBLE_EQ(hw.position_command[1], 0.2);
  EXPECT_DOUBLE_EQ(hw.velocity_command[2], 0.0);
}

// command_timeout: 10 ms after the last command (taken at t = 1 ms), the
// effort goes to 0 in the cycle at t = 11 ms; a new command restarts it.
TEST_F(ForwardTest, CommandTimeoutSetsTheEffortToZeroUntilTheNextCommand) {
  effort_controllers::JointEffortController controller;
  initController(controller, hw, makeContext("eff", "{joint: b, command_timeout: 0.01}", &bus));
  std::vector<double> published_at;
  auto subscription = bus.subscribe<Float64>("/robot/eff/command_timed_out",
                                             [&](const Float64& msg) { published_at.push_back(msg.data); });
  controller.startRequest(Time(0.0));
  bus.publish("/robot/eff/command", Float64{2.0});
  for (int k = 1; k <= 10; ++k) {
    controller.update(Time(0.001 * k), Duration(0.001));
    EXPECT_DOUBLE_EQ(hw.effort_command[1], 2.0) << "cycle " << k;
  }
  for (int k = 11; k <= 20; ++k) {
    controller.update(Time(0.001 * k), Duration(0.001));
    EXPECT_DOUBLE_EQ(hw.effort_command[1], 0.0) << "cycle " << k;
  }
  EXPECT_EQ(controller.commandTimeouts(), 1u);
  bus.publish("/robot/eff/command", Float64{-1.5});
  for (int k = 21; k <= 30; ++k) {
    controller.update(Time(0.001 * k), Duration(0.001));
    EXPECT_DOUBLE_EQ(hw.effort_command[1], -1.5) << "cycle " << k;
  }
  controller.update(Time(0.031), Duration(0.001));
  EXPECT_DOUBLE_EQ(hw.effort_command[1], 0.0);
  EXPECT_EQ(controller.commandTimeouts(), 2u);
  bus.flush();
  EXPECT_EQ(published_at, (std::vector<double>{0.001 * 11, 0.001 * 31}));
}

// A position command times out to where the joint is then, and stays there
// while the joint moves on.
TEST_F(ForwardTest, CommandTimeoutHoldsThePositionMeasuredThen) {
  position_controllers::JointPositionController controller;
  initController(controller, hw, makeContext("pos", "{joint: a, command_timeout: 0.005}", &bus));
  hw.position[0] = 0.2;
  controller.startRequest(Time(0.0));
  bus.publish("/robot/pos/command", Float64{1.0});
  controller.update(Time(0.001), Duration(0.001));
  EXPECT_DOUBLE_EQ(hw.position_command[0], 1.0);
  hw.position[0] = 0.6;
  for (int k = 2; k <= 5; ++k) controller.update(Time(0.001 * k), Duration(0.001));
  EXPECT_DOUBLE_EQ(hw.position_command[0], 1.0);
  controller.update(Time(0.006), Duration(0.001));
  EXPECT_DOUBLE_EQ(hw.position_command[0], 0.6);
  hw.position[0] = 0.9;
  controller.update(Time(0.007), Duration(0.001));
  EXPECT_DOUBLE_EQ(hw.position_command[0], 0.6);
}

TEST_F(ForwardTest, GroupVelocityCommandTimesOutToZeroAndNeverWithoutATimeout) {
  velocity_controllers::JointGroupVelocityController timed;
  velocity_controllers::JointGroupVelocityController untimed;
  initController(timed, hw, makeContext("timed", "{joints: [a, b], command_timeout: 0.002}", &bus));
  initController(untimed, hw, makeContext("untimed", "{joints: [c]}", &bus));
  timed.startRequest(Time(0.0));
  untimed.startRequest(Time(0.0));
  bus.publish("/robot/timed/command", Float64MultiArray{{0.5, -0.5}});
  bus.publish("/robot/untimed/command", Float64MultiArray{{0.25}});
  timed.update(Time(0.001), Duration(0.001));
  EXPECT_EQ(timed.commands(), (std::vector<double>{0.5, -0.5}));
  for (int k = 2; k <= 1000; ++k) {
    timed.update(Time(0.001 * k), Duration(0.001));
    untimed.update(Time(0.001 * k), Duration(0.001));
  }
  EXPECT_EQ(timed.commands(), (std::vector<double>{0.0, 0.0}));
  EXPECT_DOUBLE_EQ(hw.velocity_command[0], 0.0);
  EXPECT_EQ(timed.commandTimeouts(), 1u);
  EXPECT_DOUBLE_EQ(hw.velocity_command[2], 0.25);
  EXPECT_EQ(untimed.commandTimeouts(), 0u);
}

TEST_F(ForwardTest, CommandTimeoutMustBeSecondsOrZero) {
  effort_controllers::JointEffortController controller;
  std::vector<hardware_interface::InterfaceResources> claimed;
  for (const char* params : {"{joint: a, command_timeout: -0.1}", "{joint: a, command_timeout: .nan}",
                             "{joint: a, command_timeout: soon}", "{joint: a, command_timeout: .inf}"}) {
    try {
      controller.initRequest(&hw, makeContext("eff", params, &bus), claimed);
      ADD_FAILURE() << params << " was accepted";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("command_timeout"), std::string::npos) << e.what();
    }
  }
}

TEST_F(ForwardTest, GroupNeedsAJointList) {
  effort_controllers::JointGroupEffortController controller;
  std::vector<hardware_interface::InterfaceResources> claimed;
  for (const char* params : {"{}", "{joints: []}", "{joints: a}", "{joints: [a, a]}"}) {
    EXPECT_THROW(controller.initRequest(&hw, makeContext("group", params, &bus), claimed), ConfigError)
        << params;
  }
}

}  // namespace
}  // namespace servoloop::controllers
