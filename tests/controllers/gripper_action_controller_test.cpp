// The gripper action controllers against a finger simulated here: a 0.1 kg
// slide (joint "slide" of the test robot) with viscous damping, integrated by
// semi-implicit Euler, that stops dead at an object when there is one. Closing
// on nothing reaches the goal; closing on an object stalls after
// stall_timeout and squeezes with max_effort; cancel, preemption and the
// parameters as ros_controllers' gripper_action_controller has them.
#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "controller_test_support.hpp"
#include "servoloop/controllers/gripper_action_controller/gripper_action_controller.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/realtime/action_registry.hpp"

namespace servoloop::controllers::gripper_action_controller {
namespace {

using testing::initController;
using testing::makeContext;
using testing::TestJointsHW;
using State = servoloop::realtime::GoalState;
namespace cm = servoloop::control_msgs;

constexpr double kDt = 0.001;
constexpr double kMass = 0.1;     // kg
constexpr double kDamping = 1.0;  // N·s/m

template <class Controller>
class Finger {
 public:
  explicit Finger(const std::string& params) {
    auto context = makeContext("gripper", params, &bus);
    context.actions = &actions;
    initController(controller, hw, context);
    controller.startRequest(Time(0.0));
  }
  // One control cycle, then the finger moves for one step under the effort
  // (effort interface) or to the commanded position (position interface).
  void step() {
    now += kDt;
    controller.update(Time(now), Duration(kDt));
    double& x = hw.position[i];
    double& v = hw.velocity[i];
    if constexpr (std::is_same_v<Controller, EffortGripperActionController>) {
      v += kDt * (hw.effort_command[i] - kDamping * v) / kMass;
      x += kDt * v;
    } else {
      v = (hw.position_command[i] - x) / kDt;
      x = hw.position_command[i];
    }
    if (object && x > *object) {  // the object stops the finger dead
      x = *object;
      v = 0.0;
    }
  }
  void runFor(double seconds) {
    const double until = now + seconds;
    while (now + 0.5 * kDt < until) step();
  }
  std::shared_ptr<servoloop::realtime::ActionGoal> send(double position, double max_effort) {
    const cm::GripperCommandGoal goal{{position, max_effort}};
    return actions.sendGoal("/robot/gripper/gripper_cmd", cm::GripperCommandGoal::kActionType, &goal);
  }
  static cm::GripperCommandResult resultOf(const servoloop::realtime::ActionGoal& goal) {
    cm::GripperCommandResult result;
    goal.result(&result);
    return result;
  }

  servoloop::realtime::TopicBus bus;
  servoloop::realtime::ActionRegistry actions;
  TestJointsHW hw{{"slide"}};
  const std::size_t i = 0;
  Controller controller;
  std::optional<double> object;
  double now = 0.0;
};

constexpr const char* kEffortParams =
    "{joint: slide, gains: {slide: {p: 100, d: 5}}, goal_tolerance: 0.002, stall_timeout: 0.5, "
    "stall_velocity_threshold: 0.001}";

TEST(GripperActionController, ClosingOnNothingReachesTheGoal) {
  Finger<EffortGripperActionController> finger(kEffortParams);
  ASSERT_EQ(finger.actions.list().at(0).name, "/robot/gripper/gripper_cmd");
  auto goal = finger.send(0.04, 20.0);
  finger.runFor(0.1);
  EXPECT_EQ(goal->state(), State::active);
  cm::GripperCommandFeedback feedback;
  ASSERT_TRUE(goal->feedback(&feedback));
  EXPECT_GT(feedback.position, 0.0);
  finger.runFor(2.0);
  ASSERT_EQ(goal->state(), State::succeeded);
  const auto result = finger.resultOf(*goal);
  EXPECT_TRUE(result.reached_goal);
  EXPECT_FALSE(result.stalled);
  EXPECT_NEAR(result.position, 0.04, 0.002);
}

TEST(GripperActionController, ClosingOnAnObjectStallsAndSqueezesWithMaxEffort) {
  Finger<EffortGripperActionController> finger(kEffortParams);
  finger.object = 0.02;
  auto goal = finger.send(0.04, 1.5);
  // At the object the PID asks for 100 · 0.02 = 2 N; max_effort holds it at 1.5 N.
  double contact_time = -1.0;
  while (finger.now < 3.0 && (goal->state() == State::active || goal->state() == State::pending)) {
    finger.step();
    if (contact_time < 0.0 && finger.hw.position[0] >= 0.02) contact_time = finger.now;
  }
  ASSERT_GT(contact_time, 0.0);
  EXPECT_EQ(goal->state(), State::aborted);
  const auto result = finger.resultOf(*goal);
  EXPECT_TRUE(result.stalled);
  EXPECT_FALSE(result.reached_goal);
  EXPECT_DOUBLE_EQ(result.position, 0.02);
  EXPECT_DOUBLE_EQ(result.effort, 1.5);
  // Stalled stall_timeout after it stopped moving (at contact), to a step.
  EXPECT_NEAR(finger.now - contact_time, 0.5, 2 * kDt);
  // The command stays: it keeps squeezing.
  finger.runFor(0.5);
  EXPECT_DOUBLE_EQ(finger.hw.effort_command[0], 1.5);
}

TEST(GripperActionController, PositionInterfaceCommandsThePosition) {
  Finger<PositionGripperActionController> finger("{joint: slide}");
  auto goal = finger.send(0.03, 5.0);
  finger.step();
  EXPECT_DOUBLE_EQ(finger.hw.position_command[0], 0.03);
  finger.step();
  EXPECT_EQ(goal->state(), State::succeeded);
  EXPECT_DOUBLE_EQ(finger.resultOf(*goal).effort, 5.0);  // ros_controllers reports max_effort
}

TEST(GripperActionController, CancelHoldsAndANewGoalPreempts) {
  Finger<EffortGripperActionController> finger(kEffortParams);
  auto first = finger.send(0.04, 20.0);
  finger.runFor(0.02);
  auto second = finger.send(-0.04, 20.0);
  finger.step();
  EXPECT_EQ(first->state(), State::preempted);
  EXPECT_EQ(second->state(), State::active);
  second->cancel();
  finger.step();
  EXPECT_EQ(second->state(), State::canceled);
  EXPECT_DOUBLE_EQ(finger.controller.commandedPosition(), finger.hw.position[0] - finger.hw.velocity[0] * kDt);

  finger.controller.stopRequest(Time(finger.now));
  EXPECT_EQ(finger.hw.effort_command[0], 0.0);
  EXPECT_EQ(finger.send(0.01, 1.0)->state(), State::rejected);  // not running
}

TEST(GripperActionController, AGoalToAStoppedGripperIsRejectedWithTheReason) {
  Finger<EffortGripperActionController> finger(kEffortParams);
  finger.controller.stopRequest(Time(finger.now));
  auto goal = finger.send(0.01, 1.0);
  EXPECT_EQ(goal->state(), State::rejected);
  EXPECT_EQ(goal->statusText(), "controller 'gripper' is not running; start it with servoloop control start gripper");
}

TEST(GripperActionController, StoppingBySwitchOrFaultAbortsTheGoalWithAReason) {
  Finger<EffortGripperActionController> finger(kEffortParams);
  auto goal = finger.send(0.04, 20.0);
  finger.runFor(0.02);
  ASSERT_EQ(goal->state(), State::active);
  finger.controller.stopRequest(Time(finger.now));
  EXPECT_EQ(goal->state(), State::aborted);
  EXPECT_THAT(goal->statusText(), ::testing::HasSubstr("stopped"));

  finger.controller.startRequest(Time(finger.now));
  goal = finger.send(0.04, 20.0);
  finger.runFor(0.02);
  ASSERT_EQ(goal->state(), State::active);
  finger.controller.abortRequest();  // fault containment
  EXPECT_EQ(goal->state(), State::aborted);
  EXPECT_THAT(goal->statusText(), ::testing::HasSubstr("fault"));
  EXPECT_EQ(finger.send(0.01, 1.0)->state(), State::rejected);
}

TEST(GripperActionController, ParametersAsRosControllersNamesThem) {
  servoloop::realtime::TopicBus bus;
  TestJointsHW hw({"slide"});
  std::vector<testing::hi::InterfaceResources> claimed;
  EffortGripperActionController effort;
  EXPECT_THAT([&] { effort.initRequest(&hw, makeContext("g", "{joint: slide}", &bus), claimed); },
              ::testing::ThrowsMessage<ConfigError>(::testing::HasSubstr("gains/slide' is missing")));
  PositionGripperActionController position;
  EXPECT_THAT([&] { position.initRequest(&hw, makeContext("g", "{joint: slide, stall_timeout: -1}", &bus), claimed); },
              ::testing::ThrowsMessage<ConfigError>(::testing::HasSubstr("stall_timeout' is -1")));
  PositionGripperActionController no_joint;
  EXPECT_THAT([&] { no_joint.initRequest(&hw, makeContext("g", "{}", &bus), claimed); },
              ::testing::ThrowsMessage<ConfigError>(::testing::HasSubstr("joint")));
}

}  // namespace
}  // namespace servoloop::controllers::gripper_action_controller
