// effort_controllers/JointGroupPositionController: one PID per joint, read
// from <controller>/<joint>/pid, with the single-joint setpoint rules.
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "controller_test_support.hpp"
#include "servoloop/controllers/effort_controllers/joint_group_position_controller.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::controllers {
namespace {

using effort_controllers::JointGroupPositionController;
using testing::initController;
using testing::makeContext;
using testing::TestJointsHW;
using Float64MultiArray = servoloop::std_msgs::Float64MultiArray;

constexpr const char* kParams =
    "joints: [rev, cont]\n"
    "rev:  {pid: {p: 2.0}}\n"
    "cont: {pid: {p: 1.0, i: 4.0, i_clamp: 1.0}}\n";

TEST(EffortGroupPosition, PerJointPidAndSetpointRules) {
  servoloop::realtime::TopicBus bus;
  TestJointsHW hw({"rev", "cont"});
  JointGroupPositionController controller;
  initController(controller, hw, makeContext("group", kParams, &bus, testing::testRobotModel()));
  hw.position[0] = 1.0;
  hw.position[1] = -3.0;
  controller.startRequest(Time(0.0));
  controller.update(Time(0.01), Duration(0.01));
  EXPECT_EQ(controller.setpoints(), (std::vector<double>{1.0, -3.0}));  // hold where they are
  EXPECT_DOUBLE_EQ(hw.effort_command[0], 0.0);
  EXPECT_DOUBLE_EQ(hw.effort_command[1], 0.0);

  // rev: setpoint 5 clamped to 2, error 1, effort 2·1.
  // cont: setpoint 3 from -3, error 6 - 2π; p·e + i·(dt·e) (within the ±1 clamp).
  bus.publish("/robot/group/command", Float64MultiArray{{5.0, 3.0}});
  controller.update(Time(0.02), Duration(0.01));
  const double cont_error = 6.0 - 2.0 * std::numbers::pi;
  EXPECT_EQ(controller.setpoints(), (std::vector<double>{2.0, 3.0}));
  EXPECT_NEAR(hw.effort_command[0], 2.0, 1e-12);
  EXPECT_NEAR(hw.effort_command[1], 1.0 * cont_error + 4.0 * (0.01 * cont_error), 1e-12);

  bus.publish("/robot/group/command", Float64MultiArray{{0.5}});
  controller.update(Time(0.03), Duration(0.01));
  EXPECT_EQ(controller.setpoints(), (std::vector<double>{2.0, 3.0}));
  EXPECT_EQ(controller.rejectedWrongSizeCommands(), 1u);
}

TEST(EffortGroupPosition, EveryJointNeedsItsPid) {
  servoloop::realtime::TopicBus bus;
  TestJointsHW hw({"rev", "cont"});
  JointGroupPositionController controller;
  std::vector<hardware_interface::InterfaceResources> claimed;
  try {
    controller.initRequest(
        &hw, makeContext("group", "{joints: [rev, cont], rev: {pid: {p: 1}}}", &bus, testing::testRobotModel()),
        claimed);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("robot/group/cont/pid"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace servoloop::controllers
