// minimal_joint_controller/MinimalJointController: the seed's raw PD, its
// defaults, its own rate, and its topics.
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "controller_test_support.hpp"
#include "servoloop/controllers/minimal_joint_controller/minimal_joint_controller.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::controllers {
namespace {

using testing::initController;
using testing::makeContext;
using testing::TestJointsHW;
using Float64 = servoloop::std_msgs::Float64;
using JointStateMsg = servoloop::sensor_msgs::JointState;


class MinimalJointControllerTest : public ::testing::Test {
 protected:
  void init(const std::string& params) {
    initController(controller, hw, makeContext("pd", params, &bus, nullptr, "/one_DOF_robot"));
  }
  void command(double value) { bus.publish("/one_DOF_robot/pd/pos_cmd", Float64{value}); }

  servoloop::realtime::TopicBus bus;
  TestJointsHW hw{{"joint1", "joint2"}};
  MinimalJointController controller;
};

TEST_F(MinimalJointControllerTest, SeedDefaults) {
  init("{}");
  EXPECT_DOUBLE_EQ(controller.kp(), 10.0);
  EXPECT_DOUBLE_EQ(controller.kv(), 3.0);
  EXPECT_DOUBLE_EQ(controller.updateRate(), 100.0);
  hw.position[0] = 0.25;
  hw.velocity[0] = 0.5;
  controller.startRequest(Time(0.0));
  controller.update(Time(0.01), Duration(0.01));
  // Command 0 at start (as the seed's node): 10·(0 - 0.25) - 3·0.5 on joint1.
  EXPECT_DOUBLE_EQ(hw.effort_command[0], 10.0 * (0.0 - 0.25) - 3.0 * 0.5);
  EXPECT_DOUBLE_EQ(hw.effort_command[1], 0.0);
}

TEST_F(MinimalJointControllerTest, ErrorWrapsIntoMinusPiToPi) {
  init("{joint: joint2, kp: 2.0, kv: 0.5, update_rate: 100}");
  int cycle = 0;
  const auto effortFor = [&](double cmd, double q, double qdot) {
    hw.position[1] = q;
    hw.velocity[1] = qdot;
    command(cmd);
    ++cycle;
    controller.update(Time(0.01 * cycle), Duration(0.01));
    return hw.effort_command[1];
  };
  controller.startRequest(Time(0.0));
  // cmd 3, q -3: the error is 6 - 2π, not 6.
  EXPECT_NEAR(effortFor(3.0, -3.0, 0.5), 2.0 * (6.0 - 2.0 * std::numbers::pi) - 0.5 * 0.5, 1e-12);
  // cmd -π, q 0: (-π, π] puts the error at +π.
  EXPECT_NEAR(effortFor(-std::numbers::pi, 0.0, 0.0), 2.0 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(effortFor(std::numbers::pi, 0.0, 0.0), 2.0 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(effortFor(0.5, 0.25, -1.0), 2.0 * 0.25 + 0.5 * 1.0, 1e-12);
}

TEST_F(MinimalJointControllerTest, RunsAtItsOwnRateAndHoldsTheEffortInBetween) {
  init("{}");  // 100 Hz, inside a 1 kHz loop that calls it every cycle
  controller.startRequest(Time(0.0));
  std::vector<int> control_updates;
  for (int k = 1; k <= 25; ++k) {
    hw.position[0] = 0.01 * k;  // moves every cycle; the effort must not follow in between
    hw.effort_command[0] = 123.0;  // something else wrote: the held effort is written again
    const auto before = controller.controlUpdates();
    controller.update(Time(0.001 * k), Duration(0.001));
    if (controller.controlUpdates() != before) control_updates.push_back(k);
    const int last_update = control_updates.back();
    EXPECT_DOUBLE_EQ(hw.effort_command[0], 10.0 * (0.0 - 0.01 * last_update)) << "cycle " << k;
  }
  EXPECT_EQ(control_updates, (std::vector<int>{1, 11, 21}));
}

TEST_F(MinimalJointControllerTest, PublishesItsTopicsEachControlUpdate) {
  init("{joint: joint1}");
  std::vector<double> positions, velocities, efforts;
  std::vector<JointStateMsg> joint_states;
  auto s1 = bus.subscribe<Float64>("/one_DOF_robot/pd/jnt_pos", [&](const Float64& m) { positions.push_back(m.data); });
  auto s2 = bus.subscribe<Float64>("/one_DOF_robot/pd/jnt_vel", [&](const Float64& m) { velocities.push_back(m.data); });
  auto s3 = bus.subscribe<Float64>("/one_DOF_robot/pd/jnt_trq", [&](const Float64& m) { efforts.push_back(m.data); });
  auto s4 = bus.subscribe<JointStateMsg>("/one_DOF_robot/joint_states",
                                         [&](const JointStateMsg& m) { joint_states.push_back(m); });
  hw.position[0] = 1.0;
  hw.velocity[0] = -0.2;
  controller.startRequest(Time(0.0));
  command(1.5);
  for (int k = 1; k <= 20; ++k) controller.update(Time(0.001 * k), Duration(0.001));  // updates 1 and 11
  bus.flush();
  const double expected_effort = 10.0 * 0.5 - 3.0 * (-0.2);
  EXPECT_EQ(positions, (std::vector<double>{1.0, 1.0}));
  EXPECT_EQ(velocities, (std::vector<double>{-0.2, -0.2}));
  ASSERT_EQ(efforts.size(), 2u);
  EXPECT_DOUBLE_EQ(efforts[0], expected_effort);
  ASSERT_EQ(joint_states.size(), 2u);
  EXPECT_EQ(joint_states[0].name, (std::vector<std::string>{"joint1"}));
  EXPECT_EQ(joint_states[0].position, (std::vector<double>{1.0}));
  EXPECT_EQ(joint_states[0].velocity, (std::vector<double>{-0.2}));
  EXPECT_TRUE(joint_states[0].effort.empty());
  EXPECT_DOUBLE_EQ(joint_states[1].stamp, 0.011);
}

TEST_F(MinimalJointControllerTest, NonFiniteCommandIsIgnored) {
  init("{}");
  controller.startRequest(Time(0.0));
  command(1.0);
  controller.update(Time(0.01), Duration(0.01));
  command(std::numeric_limits<double>::quiet_NaN());
  controller.update(Time(0.02), Duration(0.01));
  EXPECT_DOUBLE_EQ(controller.positionCommand(), 1.0);
  EXPECT_DOUBLE_EQ(hw.effort_command[0], 10.0);
  EXPECT_EQ(controller.rejectedNonFiniteCommands(), 1u);
}

TEST_F(MinimalJointControllerTest, BadParametersNameTheKey) {
  std::vector<hardware_interface::InterfaceResources> claimed;
  for (const auto& [params, fragment] : std::vector<std::pair<std::string, std::string>>{
           {"{update_rate: 0}", "one_DOF_robot/pd/update_rate"},
           {"{kp: fast}", "one_DOF_robot/pd/kp"},
           {"{joint: joint9}", "'joint9'"}}) {
    MinimalJointController fresh;
    try {
      fresh.initRequest(&hw, makeContext("pd", params, &bus, nullptr, "/one_DOF_robot"), claimed);
      ADD_FAILURE() << "expected ConfigError for " << params;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace servoloop::controllers
