// The joint trajectory controllers (position, velocity and effort) against
// hand calculations: the commands each interface gets, trajectories from the
// topic in any joint order, partial trajectories, replacement, the stop
// profile of stop_trajectory_duration, and a goal's path and goal tolerances
// with control_msgs/FollowJointTrajectoryResult's error codes.
#include <atomic>
#include <cmath>
#include <thread>
#include <memory>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "../common/log_capture.hpp"
#include "controller_test_support.hpp"
#include "servoloop/controllers/joint_trajectory_controller/joint_trajectory_controller.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/realtime/action_messages.hpp"
#include "servoloop/realtime/action_registry.hpp"

namespace servoloop::controllers::joint_trajectory_controller {
namespace {

using testing::initController;
using testing::makeContext;
using testing::TestJointsHW;
using TrajectoryMsg = servoloop::trajectory_msgs::JointTrajectory;
using PointMsg = servoloop::trajectory_msgs::JointTrajectoryPoint;
using StateMsg = servoloop::control_msgs::JointTrajectoryControllerState;

constexpr double kDt = 0.001;

PointMsg pointMsg(std::vector<double> positions, double time_from_start, std::vector<double> velocities = {}) {
  PointMsg point;
  point.positions = std::move(positions);
  point.velocities = std::move(velocities);
  point.time_from_start = time_from_start;
  return point;
}

TrajectoryMsg trajectoryMsg(std::vector<std::string> joints, std::vector<PointMsg> points, double stamp = 0.0) {
  TrajectoryMsg msg;
  msg.stamp = stamp;
  msg.joint_names = std::move(joints);
  msg.points = std::move(points);
  return msg;
}

// A controller on the test hardware's joints "rev" (revolute, [0, 2]) and
// "cont" (continuous), run one update per millisecond of control time.
template <class Controller>
class Fixture {
 public:
  explicit Fixture(const std::string& params) {
    initController(controller, hw, makeContext("arm", params, &bus, testing::testRobotModel()));
  }
  void start() {
    controller.startRequest(Time(now));
  }
  // Runs updates until control time `until` (inclusive of the last step).
  void runUntil(double until) {
    while (now + 0.5 * kDt < until) step();
  }
  void step() {
    now += kDt;
    bus.setTime(Time(now));
    ASSERT_EQ(controller.update(Time(now), Duration(kDt)), ReturnType::ok);
  }
  void send(const TrajectoryMsg& msg) {
    bus.publish("/robot/arm/command", msg);
    bus.flush();
  }
  double desired(std::size_t j) const { return controller_follower().desired()[j].position; }
  double desiredVelocity(std::size_t j) const { return controller_follower().desired()[j].velocity; }
  const TrajectoryFollower& controller_follower() const {
    return const_cast<Controller&>(controller).follower();
  }

  servoloop::realtime::TopicBus bus;
  TestJointsHW hw{{"rev", "cont"}};
  Controller controller;
  double now = 0.0;
};

constexpr const char* kPositionParams = "{joints: [rev, cont]}";

TEST(JointTrajectoryController, StartingHoldsTheCurrentPosition) {
  Fixture<PositionJointTrajectoryController> f(kPositionParams);
  f.hw.position = {0.7, -1.2};
  f.start();
  f.runUntil(0.1);
  EXPECT_DOUBLE_EQ(f.hw.position_command[0], 0.7);
  EXPECT_DOUBLE_EQ(f.hw.position_command[1], -1.2);
}

TEST(JointTrajectoryController, PositionInterfaceFollowsTheLinearInterpolationInAnyJointOrder) {
  Fixture<PositionJointTrajectoryController> f(kPositionParams);
  f.hw.position = {0.5, 0.0};
  f.start();
  // Joint order reversed in the message: cont first. Points at 1 s and 2 s
  // after arrival (stamp 0), taken over at the next update (t = 1 ms).
  f.send(trajectoryMsg({"cont", "rev"}, {pointMsg({1.0, 1.5}, 1.0), pointMsg({-1.0, 0.5}, 2.0)}));
  f.step();
  const double start = f.now;
  ASSERT_TRUE(f.controller.follower().following());
  f.runUntil(start + 0.5);
  // Half way to the first point: rev 0.5 → 1.5, cont 0 → 1.
  EXPECT_NEAR(f.hw.position_command[0], 1.0, 1e-9);
  EXPECT_NEAR(f.hw.position_command[1], 0.5, 1e-9);
  f.runUntil(start + 1.25);
  EXPECT_NEAR(f.hw.position_command[0], 1.5 - 0.25, 1e-9);
  EXPECT_NEAR(f.hw.position_command[1], 1.0 - 0.5, 1e-9);
  f.runUntil(start + 3.0);  // after the end: the last point
  EXPECT_NEAR(f.hw.position_command[0], 0.5, 1e-12);
  EXPECT_NEAR(f.hw.position_command[1], -1.0, 1e-12);
}

TEST(JointTrajectoryController, CubicSegmentsMatchTheirPolynomial) {
  Fixture<PositionJointTrajectoryController> f(kPositionParams);
  f.start();
  f.step();
  const double t0 = f.now;
  // Starting 10 ms from now at rest at 0, then to 1 rad at rest in 2 s:
  // x(t) = 3(t/2)² − 2(t/2)³ from the start.
  const double start = t0 + 0.01;
  f.send(trajectoryMsg({"rev", "cont"}, {pointMsg({0.0, 0.0}, 0.0, {0.0, 0.0}), pointMsg({1.0, 0.0}, 2.0, {0.0, 0.0})},
                       start));
  for (double t : {0.3, 1.0, 1.7}) {
    f.runUntil(start + t);
    const double s = (f.now - start) / 2.0;
    EXPECT_NEAR(f.hw.position_command[0], 3 * s * s - 2 * s * s * s, 1e-9) << "t = " << t;
    EXPECT_NEAR(f.desiredVelocity(0), (6 * s - 6 * s * s) / 2.0, 1e-9) << "t = " << t;
  }
}

TEST(JointTrajectoryController, ContinuousJointTakesTheShortWayRound) {
  Fixture<PositionJointTrajectoryController> f(kPositionParams);
  f.hw.position = {0.0, 3.0};
  f.start();
  f.send(trajectoryMsg({"rev", "cont"}, {pointMsg({0.0, -3.0}, 1.0)}));
  f.step();
  f.runUntil(1.001);
  // −3 is 2π − 6 ≈ 0.283 rad ahead of 3 the short way: the command ends at 3 + 0.283.
  EXPECT_NEAR(f.hw.position_command[1], -3.0 + 2.0 * M_PI, 1e-9);
}

TEST(JointTrajectoryController, PartialTrajectoriesAreRefusedUnlessAllowed) {
  Fixture<PositionJointTrajectoryController> strict(kPositionParams);
  strict.hw.position = {0.2, 0.3};
  strict.start();
  strict.send(trajectoryMsg({"rev"}, {pointMsg({1.0}, 1.0)}));
  strict.runUntil(1.5);
  EXPECT_FALSE(strict.controller.follower().following());
  EXPECT_EQ(strict.controller.follower().trajectoriesRefused(), 1u);
  EXPECT_DOUBLE_EQ(strict.hw.position_command[0], 0.2);

  Fixture<PositionJointTrajectoryController> partial("{joints: [rev, cont], allow_partial_joints_goal: true}");
  partial.hw.position = {0.2, 0.3};
  partial.start();
  partial.send(trajectoryMsg({"rev"}, {pointMsg({1.0}, 1.0)}));
  partial.runUntil(1.5);
  EXPECT_NEAR(partial.hw.position_command[0], 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(partial.hw.position_command[1], 0.3);  // left out: holds
}

TEST(JointTrajectoryController, BadTrajectoriesAreRefusedAndTheControllerKeepsItsCourse) {
  Fixture<PositionJointTrajectoryController> f(kPositionParams);
  f.hw.position = {0.2, 0.3};
  f.start();
  f.runUntil(1.0);
  f.send(trajectoryMsg({"rev", "nope"}, {pointMsg({1.0, 1.0}, 1.0)}));                      // unknown joint
  f.send(trajectoryMsg({"rev", "cont"}, {pointMsg({1.0}, 1.0)}));                           // too few values
  f.send(trajectoryMsg({"rev", "cont"}, {pointMsg({1.0, NAN}, 1.0)}));                      // not finite
  f.send(trajectoryMsg({"rev", "cont"}, {pointMsg({1.0, 1.0}, 2.0), pointMsg({1, 1}, 1.0)}));  // time goes back
  f.send(trajectoryMsg({"rev", "cont"}, {pointMsg({1.0, 1.0}, 0.5)}, 0.2));                 // ends in the past
  f.runUntil(2.0);
  EXPECT_EQ(f.controller.follower().trajectoriesRefused(), 5u);
  EXPECT_EQ(f.controller.follower().trajectoriesTaken(), 0u);
  EXPECT_DOUBLE_EQ(f.hw.position_command[0], 0.2);
}

TEST(JointTrajectoryController, ReplacementMidSegmentIsContinuous) {
  Fixture<PositionJointTrajectoryController> f(kPositionParams);
  f.start();
  f.send(trajectoryMsg({"rev", "cont"}, {pointMsg({1.5, 1.0}, 1.0, {0.0, 0.0})}));
  f.runUntil(0.5);
  const double position_before = f.desired(0);
  const double velocity_before = f.desiredVelocity(0);
  ASSERT_GT(velocity_before, 1.0);  // mid-motion
  f.send(trajectoryMsg({"rev", "cont"}, {pointMsg({0.0, 0.0}, 1.0, {0.0, 0.0})}));
  f.step();
  // One step on from the old trajectory's state: position moves by about v·dt, velocity stays.
  EXPECT_NEAR(f.desired(0), position_before + velocity_before * kDt, 1e-5);
  EXPECT_NEAR(f.desiredVelocity(0), velocity_before, 0.01);
}

TEST(JointTrajectoryController, AnEmptyTrajectoryStopsWithinStopTrajectoryDuration) {
  // The stop profile: the quintic from (p, v, 0) to (p, −v, 0) over 2T is at
  // rest at T, at p + 5vT/8 (by hand: x(s) = p + 2vT(s − 2s³ + s⁴), s = t/2T).
  Fixture<PositionJointTrajectoryController> f("{joints: [rev, cont], stop_trajectory_duration: 0.4}");
  f.start();
  f.send(trajectoryMsg({"rev", "cont"}, {pointMsg({10.0, 0.0}, 10.0)}));  // rev at 1 rad/s
  f.runUntil(1.0);
  const double p = f.desired(0);
  const double v = f.desiredVelocity(0);
  ASSERT_NEAR(v, 1.0, 1e-9);
  f.send(trajectoryMsg({"rev", "cont"}, {}));
  f.step();  // the stop is taken here, from the state at this time
  const double p0 = p + v * kDt;
  f.runUntil(f.now + 0.4);
  EXPECT_NEAR(f.desired(0), p0 + 5.0 * v * 0.4 / 8.0, 1e-6);
  EXPECT_NEAR(f.desiredVelocity(0), 0.0, 1e-9);
  f.runUntil(f.now + 1.0);
  EXPECT_NEAR(f.desired(0), p0 + 5.0 * v * 0.4 / 8.0, 1e-6);
}

TEST(JointTrajectoryController, VelocityInterfaceIsFeedForwardPlusPid) {
  Fixture<VelocityJointTrajectoryController> f(
      "{joints: [rev, cont], gains: {rev: {p: 2.0}, cont: {p: 3.0, d: 0.5}}, velocity_ff: {rev: 1.0}}");
  f.hw.position = {0.0, 0.0};
  f.start();
  f.send(trajectoryMsg({"rev", "cont"}, {pointMsg({1.0, 2.0}, 1.0)}));  // 1 and 2 rad/s
  f.step();
  f.runUntil(0.5);
  // The joints did not move: position errors are the desired positions.
  const double e0 = f.desired(0), e1 = f.desired(1);
  EXPECT_NEAR(f.hw.velocity_command[0], 1.0 * 1.0 + 2.0 * e0, 1e-9);
  EXPECT_NEAR(f.hw.velocity_command[1], 0.0 * 2.0 + 3.0 * e1 + 0.5 * 2.0, 1e-9);
  f.controller.stopRequest(Time(f.now));
  EXPECT_EQ(f.hw.velocity_command[0], 0.0);
}

TEST(JointTrajectoryController, EffortInterfaceIsPidOnPositionAndVelocityErrors) {
  Fixture<EffortJointTrajectoryController> f("{joints: [rev, cont], gains: {rev: {p: 100, d: 10}, cont: {p: 1}}}");
  f.hw.position = {0.1, 0.0};
  f.hw.velocity = {0.3, 0.0};
  f.start();
  f.send(trajectoryMsg({"rev", "cont"}, {pointMsg({1.1, 0.0}, 1.0)}));  // rev at 1 rad/s
  f.runUntil(0.25);
  const double position_error = f.desired(0) - 0.1;
  const double velocity_error = f.desiredVelocity(0) - 0.3;
  EXPECT_NEAR(f.hw.effort_command[0], 100.0 * position_error + 10.0 * velocity_error, 1e-9);
}

TEST(JointTrajectoryController, VelocityAndEffortNeedGainsForEveryJoint) {
  servoloop::realtime::TopicBus bus;
  TestJointsHW hw({"rev", "cont"});
  EffortJointTrajectoryController controller;
  std::vector<testing::hi::InterfaceResources> claimed;
  try {
    controller.initRequest(&hw, makeContext("arm", "{joints: [rev, cont], gains: {rev: {p: 1}}}", &bus), claimed);
    FAIL() << "missing gains were accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("robot/arm/gains/cont' is missing"), std::string::npos) << e.what();
  }
}

TEST(JointTrajectoryController, ConstraintsAreReadAsRosControllersReadsThem) {
  Fixture<PositionJointTrajectoryController> f(
      "{joints: [rev, cont], constraints: {goal_time: 0.6, stopped_velocity_tolerance: 0.05, "
      "rev: {trajectory: 0.1, goal: 0.02}}}");
  const TrajectoryTolerances& t = f.controller.follower().defaultTolerances();
  EXPECT_DOUBLE_EQ(t.goal_time, 0.6);
  EXPECT_DOUBLE_EQ(t.path[0].position, 0.1);
  EXPECT_DOUBLE_EQ(t.goal[0].position, 0.02);
  EXPECT_DOUBLE_EQ(t.goal[0].velocity, 0.05);
  EXPECT_DOUBLE_EQ(t.path[1].position, 0.0);  // not given: not checked
  EXPECT_DOUBLE_EQ(t.goal[1].velocity, 0.05);

  // A goal's own tolerances: > 0 replaces, 0 keeps, < 0 turns the check off.
  const TrajectoryTolerances g =
      applyGoalTolerances(t, {"rev", "cont"}, {{"rev", -1.0, 0.0, 0.0}}, {{"cont", 0.3, 0.0, 0.0}}, 0.0);
  EXPECT_DOUBLE_EQ(g.path[0].position, 0.0);
  EXPECT_DOUBLE_EQ(g.goal[1].position, 0.3);
  EXPECT_DOUBLE_EQ(g.goal_time, 0.6);

  servoloop::realtime::TopicBus bus;
  TestJointsHW hw({"rev", "cont"});
  PositionJointTrajectoryController controller;
  std::vector<testing::hi::InterfaceResources> claimed;
  EXPECT_THROW(controller.initRequest(&hw, makeContext("arm", "{joints: [rev], constraints: {elbow: {goal: 1}}}", &bus),
                                      claimed),
               ConfigError);
}

// --- goals -----------------------------------------------------------------------------

class GoalTest : public ::testing::Test {
 protected:
  GoalTest() : f("{joints: [rev, cont], stop_trajectory_duration: 0.2}") {}
  std::shared_ptr<TrajectoryGoal> submit(const TrajectoryMsg& msg, double path = 0.0, double goal = 0.0,
                                         double goal_time = 0.0) {
    TrajectoryTolerances tolerances = f.controller.follower().defaultTolerances();
    for (auto& t : tolerances.path) t.position = path;
    for (auto& t : tolerances.goal) t.position = goal;
    tolerances.goal_time = goal_time;
    return f.controller.follower().submitGoal(msg, tolerances);
  }
  // The joints follow their position commands exactly, offset by `lag` on rev.
  void track(double until, double lag = 0.0) {
    while (f.now + 0.5 * kDt < until) {
      f.step();
      f.hw.position = {f.hw.position_command[0] - lag, f.hw.position_command[1]};
      f.hw.velocity = {f.desiredVelocity(0), f.desiredVelocity(1)};
    }
  }
  Fixture<PositionJointTrajectoryController> f;
};

TEST_F(GoalTest, AGoalFollowedWithinItsTolerancesSucceeds) {
  f.start();
  auto goal = submit(trajectoryMsg({"rev", "cont"}, {pointMsg({1.0, 1.0}, 1.0, {0.0, 0.0})}), 0.05, 0.01);
  EXPECT_EQ(goal->status(), GoalStatus::pending);
  track(0.5);
  EXPECT_EQ(goal->status(), GoalStatus::active);
  track(1.1);
  EXPECT_EQ(goal->status(), GoalStatus::succeeded);
  EXPECT_EQ(goal->errorCode(), TrajectoryErrorCode::successful);
}

TEST_F(GoalTest, LeavingThePathToleranceAbortsWithItsCodeAndStops) {
  f.start();
  auto goal = submit(trajectoryMsg({"rev", "cont"}, {pointMsg({1.0, 0.0}, 1.0)}), 0.05);
  track(0.3, 0.1);  // rev lags 0.1 rad behind: more than 0.05
  EXPECT_EQ(goal->status(), GoalStatus::aborted);
  EXPECT_EQ(goal->errorCode(), TrajectoryErrorCode::path_tolerance_violated);
  EXPECT_EQ(static_cast<int>(goal->errorCode()), -4);
  EXPECT_EQ(goal->violatingJoint(), 0);
  EXPECT_FALSE(f.controller.follower().following());
  track(1.0);
  EXPECT_NEAR(f.desiredVelocity(0), 0.0, 1e-9);  // came to rest
  EXPECT_LT(f.desired(0), 0.5);                  // and did not go on to 1.0
}

TEST_F(GoalTest, MissingTheGoalToleranceAfterGoalTimeAbortsWithItsCode) {
  f.start();
  auto goal = submit(trajectoryMsg({"rev", "cont"}, {pointMsg({1.0, 0.0}, 1.0)}), 0.0, 0.01, 0.2);
  track(1.1, 0.05);  // 0.05 rad short at the end, for longer than goal_time
  EXPECT_EQ(goal->status(), GoalStatus::active);  // still within goal_time
  track(1.25, 0.05);
  EXPECT_EQ(goal->status(), GoalStatus::aborted);
  EXPECT_EQ(static_cast<int>(goal->errorCode()), -5);
}

TEST_F(GoalTest, GoalsArePreemptedCanceledAndRejected) {
  f.start();
  auto first = submit(trajectoryMsg({"rev", "cont"}, {pointMsg({1.0, 0.0}, 1.0)}));
  track(0.2);
  auto second = submit(trajectoryMsg({"rev", "cont"}, {pointMsg({0.5, 0.0}, 1.0)}));
  track(0.3);
  EXPECT_EQ(first->status(), GoalStatus::preempted);
  EXPECT_EQ(second->status(), GoalStatus::active);
  second->requestCancel();
  track(0.31);
  EXPECT_EQ(second->status(), GoalStatus::canceled);
  track(0.6);
  EXPECT_NEAR(f.desiredVelocity(0), 0.0, 1e-9);

  auto bad = submit(trajectoryMsg({"rev", "elbow"}, {pointMsg({1.0, 0.0}, 1.0)}));
  EXPECT_EQ(bad->status(), GoalStatus::rejected);
  EXPECT_EQ(static_cast<int>(bad->errorCode()), -2);
  EXPECT_NE(bad->errorString().find("'elbow' is not a joint of the controller"), std::string::npos);
  auto old = submit(trajectoryMsg({"rev", "cont"}, {pointMsg({1.0, 0.0}, 0.1)}, 0.1));
  EXPECT_EQ(static_cast<int>(old->errorCode()), -3);

  // A goal with no points is a stop: it succeeds once taken.
  auto stop = submit(trajectoryMsg({"rev", "cont"}, {}));
  track(0.7);
  EXPECT_EQ(stop->status(), GoalStatus::succeeded);

  f.controller.stopRequest(Time(f.now));
  auto stopped = submit(trajectoryMsg({"rev", "cont"}, {pointMsg({1.0, 0.0}, 1.0)}));
  EXPECT_EQ(stopped->status(), GoalStatus::rejected);
}

TEST(JointTrajectoryController, StatePublishesDesiredActualAndError) {
  Fixture<PositionJointTrajectoryController> f("{joints: [rev, cont], state_publish_rate: 100}");
  std::vector<StateMsg> states;
  auto subscription = f.bus.subscribe<StateMsg>("/robot/arm/state", [&](const StateMsg& msg) { states.push_back(msg); });
  f.hw.position = {0.25, 0.0};
  f.start();
  f.runUntil(0.1);
  f.bus.flush();
  ASSERT_EQ(states.size(), 10u);  // 100 Hz for 0.1 s
  const StateMsg& last = states.back();
  ASSERT_EQ(last.joint_names, (std::vector<std::string>{"rev", "cont"}));
  EXPECT_DOUBLE_EQ(last.desired.positions[0], 0.25);
  EXPECT_DOUBLE_EQ(last.actual.positions[0], 0.25);
  EXPECT_DOUBLE_EQ(last.error.positions[0], 0.0);
}

// --- the follow_joint_trajectory action ---------------------------------------------------

class ActionTest : public ::testing::Test {
 protected:
  ActionTest() {
    auto context = makeContext("arm", "{joints: [rev, cont], action_monitor_rate: 100}", &bus, testing::testRobotModel());
    context.actions = &actions;
    controller = std::make_unique<PositionJointTrajectoryController>();
    initController(*controller, hw, context);
    controller->startRequest(Time(0.0));
  }
  std::shared_ptr<servoloop::realtime::ActionGoal> send(const servoloop::control_msgs::FollowJointTrajectoryGoal& goal) {
    return actions.sendGoal("/robot/arm/follow_joint_trajectory", goal.kActionType, &goal);
  }
  void step() {
    now += kDt;
    controller->update(Time(now), Duration(kDt));
  }
  static servoloop::control_msgs::FollowJointTrajectoryGoal goalTo(double rev, double time) {
    servoloop::control_msgs::FollowJointTrajectoryGoal goal;
    goal.trajectory = trajectoryMsg({"rev", "cont"}, {pointMsg({rev, 0.0}, time)});
    return goal;
  }

  servoloop::realtime::TopicBus bus;
  servoloop::realtime::ActionRegistry actions;
  TestJointsHW hw{{"rev", "cont"}};
  std::unique_ptr<PositionJointTrajectoryController> controller;
  double now = 0.0;
};

TEST_F(ActionTest, ServedUnderTheControllersNameWithFeedbackAndResult) {
  ASSERT_EQ(actions.list().size(), 1u);
  EXPECT_EQ(actions.list()[0].name, "/robot/arm/follow_joint_trajectory");
  EXPECT_EQ(actions.list()[0].type, "control_msgs/FollowJointTrajectory");

  auto goal = send(goalTo(1.0, 0.5));
  servoloop::control_msgs::FollowJointTrajectoryFeedback feedback;
  EXPECT_FALSE(goal->feedback(&feedback));  // not taken over yet
  for (int k = 0; k < 100; ++k) {
    step();
    hw.position[0] = hw.position_command[0];  // an ideal joint
  }
  ASSERT_TRUE(goal->feedback(&feedback));
  EXPECT_EQ(feedback.joint_names, (std::vector<std::string>{"rev", "cont"}));
  // Feedback at 100 Hz: the newest is from the 91st update (t = 0.091 s).
  EXPECT_NEAR(feedback.stamp, 0.091, 1e-9);
  EXPECT_NEAR(feedback.desired.positions[0], 1.0 * (0.091 - 0.001) / 0.5, 1e-9);
  EXPECT_EQ(goal->state(), servoloop::realtime::GoalState::active);
  while (now < 0.6) {
    step();
    hw.position[0] = hw.position_command[0];
  }
  EXPECT_EQ(goal->state(), servoloop::realtime::GoalState::succeeded);
  servoloop::control_msgs::FollowJointTrajectoryResult result;
  goal->result(&result);
  EXPECT_EQ(result.error_code, 0);
}

TEST_F(ActionTest, APathToleranceBrokenOnTheFirstUpdateAbortsCleanly) {
  // The controller holds 0; the joint is pushed 0.5 rad away: the goal's
  // first update (which also writes feedback) breaks a 0.01 rad path tolerance.
  hw.position[0] = 0.5;
  auto goal_message = goalTo(1.0, 1.0);
  goal_message.path_tolerance = {{"rev", 0.01, 0.0, 0.0}};
  auto goal = send(goal_message);
  step();
  EXPECT_EQ(goal->state(), servoloop::realtime::GoalState::aborted);
  servoloop::control_msgs::FollowJointTrajectoryResult result;
  goal->result(&result);
  EXPECT_EQ(result.error_code, -4);
  step();  // holding: still fine
}

TEST_F(ActionTest, ToleranceForAnUnknownJointIsRejectedAndGoalsOutliveTheController) {
  auto goal_message = goalTo(1.0, 1.0);
  goal_message.goal_tolerance = {{"elbow", 0.1, 0.0, 0.0}};
  auto rejected = send(goal_message);
  EXPECT_EQ(rejected->state(), servoloop::realtime::GoalState::rejected);
  servoloop::control_msgs::FollowJointTrajectoryResult result;
  rejected->result(&result);
  EXPECT_EQ(result.error_code, -1);
  EXPECT_THAT(result.error_string, ::testing::HasSubstr("'elbow'"));

  auto running = send(goalTo(1.0, 1.0));
  step();
  controller->stopRequest(Time(now));
  EXPECT_EQ(running->state(), servoloop::realtime::GoalState::preempted);
  controller.reset();  // unloaded
  EXPECT_TRUE(actions.list().empty());
  servoloop::control_msgs::FollowJointTrajectoryFeedback feedback;
  EXPECT_TRUE(running->feedback(&feedback));  // what it last had
  running->cancel();                          // nothing to cancel any more: no crash
}

// Trajectories, goals and cancels from two other threads while the control
// thread runs freely, with no hand-shake: every goal ends or is still the
// running one, and the action's feedback is read while it is written. (The
// ThreadSanitizer lane runs this test.)
TEST_F(ActionTest, GoalsTopicTrajectoriesAndCancelsRaceTheControlThread) {
  bus.start();
  std::atomic<bool> done{false};
  std::thread control([&] {
    for (int k = 0; k < 200000; ++k) {
      step();
      hw.position[0] = hw.position_command[0];
    }
    done = true;
  });
  std::thread topic([&] {
    for (int n = 0; !done; ++n) {
      bus.publish("/robot/arm/command", trajectoryMsg({"rev", "cont"}, {pointMsg({0.1 * (n % 5), 0.0}, 0.05)}));
      std::this_thread::yield();
    }
  });
  std::vector<std::shared_ptr<servoloop::realtime::ActionGoal>> goals;
  servoloop::control_msgs::FollowJointTrajectoryFeedback feedback;
  for (int n = 0; !done; ++n) {
    goals.push_back(send(goalTo(0.2 * (n % 4), 0.02)));
    if (n % 3 == 0) goals.back()->cancel();
    goals[goals.size() / 2]->feedback(&feedback);
    std::this_thread::yield();
  }
  control.join();
  topic.join();
  bus.stop();
  // The control thread may stop holding a goal while the next one still
  // waits (sent in the loop's last round): every earlier goal has ended.
  ASSERT_GT(goals.size(), 2u);
  for (std::size_t i = 0; i + 2 < goals.size(); ++i) {
    EXPECT_TRUE(servoloop::realtime::goalDone(goals[i]->state())) << i << " of " << goals.size();
  }
  int running = 0;
  for (const auto& goal : goals) running += goal->state() == servoloop::realtime::GoalState::active;
  EXPECT_LE(running, 1);
}


// --- goals that must never be left without a result ------------------------------------

servoloop::control_msgs::FollowJointTrajectoryResult resultOf(const servoloop::realtime::ActionGoal& goal) {
  servoloop::control_msgs::FollowJointTrajectoryResult result;
  goal.result(&result);
  return result;
}

TEST_F(ActionTest, NonFiniteAndOverflowingGoalsAreRejectedNamingTheJointAndPoint) {
  // 1e308 with velocities: the cubic's coefficients overflow (3e308).
  servoloop::control_msgs::FollowJointTrajectoryGoal huge;
  huge.trajectory = trajectoryMsg({"cont", "rev"}, {pointMsg({0.0, 0.5}, 0.5, {0.0, 0.0}),
                                                    pointMsg({0.0, 1e308}, 1.0, {0.0, 0.0})});
  auto goal = send(huge);
  EXPECT_EQ(goal->state(), servoloop::realtime::GoalState::rejected);
  auto result = resultOf(*goal);
  EXPECT_EQ(result.error_code, -1);
  EXPECT_THAT(result.error_string, ::testing::HasSubstr("joint 'rev'"));
  EXPECT_THAT(result.error_string, ::testing::HasSubstr("points[1]"));
  EXPECT_THAT(goal->statusText(), ::testing::HasSubstr("overflows"));

  servoloop::control_msgs::FollowJointTrajectoryGoal nan;
  nan.trajectory = trajectoryMsg({"rev", "cont"}, {pointMsg({0.1, std::nan("")}, 1.0)});
  goal = send(nan);
  EXPECT_EQ(goal->state(), servoloop::realtime::GoalState::rejected);
  result = resultOf(*goal);
  EXPECT_THAT(result.error_string, ::testing::HasSubstr("points[0].positions[1] (joint 'cont'"));
  EXPECT_THAT(result.error_string, ::testing::HasSubstr("not a finite number"));

  // Nothing was taken over: the controller holds finite commands.
  step();
  EXPECT_TRUE(std::isfinite(hw.position_command[0]));
}

TEST_F(ActionTest, ADesiredStateThatOverflowsAbortsTheGoalWithAReasonAndHolds) {
  servoloop::test::LogCapture log;
  while (now < 1.0 - 0.5 * kDt) step();
  hw.position[0] = 0.3;
  // Fine from rest over its 1 s, but led in over the 9 ms left of it (its
  // stamp is in the past) the cubic overflows.
  servoloop::control_msgs::FollowJointTrajectoryGoal message;
  message.trajectory = trajectoryMsg({"rev", "cont"}, {pointMsg({1e306, 0.0}, 1.0, {0.0, 0.0})}, now - 0.99);
  auto goal = send(message);
  ASSERT_EQ(goal->state(), servoloop::realtime::GoalState::pending);
  step();
  EXPECT_EQ(goal->state(), servoloop::realtime::GoalState::aborted);
  const auto result = resultOf(*goal);
  EXPECT_EQ(result.error_code, -1);
  EXPECT_THAT(result.error_string, ::testing::HasSubstr("non-finite"));
  EXPECT_TRUE(std::isfinite(hw.position_command[0]));
  EXPECT_TRUE(std::isfinite(hw.position_command[1]));
  EXPECT_NEAR(hw.position_command[0], 0.3, 1e-9);  // holds where the joint is
  EXPECT_EQ(controller->follower().nonFiniteDesiredStates(), 1u);
  bus.flush();  // the warning is logged on the delivery thread
  EXPECT_EQ(log.count("became non-finite"), 1u);
  step();
  EXPECT_TRUE(std::isfinite(hw.position_command[0]));
}

TEST_F(ActionTest, AFaultAbortsTheRunningGoalWithAResultAndLaterGoalsAreRejected) {
  auto goal = send(goalTo(1.0, 1.0));
  step();
  ASSERT_EQ(goal->state(), servoloop::realtime::GoalState::active);
  controller->abortRequest();  // what fault containment does (non-finite command, hardware failure)
  EXPECT_TRUE(controller->isFailed());
  EXPECT_EQ(goal->state(), servoloop::realtime::GoalState::aborted);
  EXPECT_THAT(resultOf(*goal).error_string, ::testing::HasSubstr("fault"));
  auto later = send(goalTo(1.0, 1.0));
  EXPECT_EQ(later->state(), servoloop::realtime::GoalState::rejected);
  EXPECT_THAT(resultOf(*later).error_string, ::testing::HasSubstr("is not running"));
}

// As ros_controllers' stopping(): the running goal is preempted (with the
// reason); one not taken over yet is aborted.
TEST_F(ActionTest, ASwitchThatStopsTheControllerPreemptsTheRunningGoalAndAbortsAWaitingOne) {
  auto running = send(goalTo(1.0, 1.0));
  step();
  ASSERT_EQ(running->state(), servoloop::realtime::GoalState::active);
  auto waiting = send(goalTo(0.5, 1.0));  // not taken over yet
  controller->stopRequest(Time(now));
  EXPECT_EQ(running->state(), servoloop::realtime::GoalState::preempted);
  EXPECT_THAT(resultOf(*running).error_string, ::testing::HasSubstr("stopped"));
  EXPECT_EQ(waiting->state(), servoloop::realtime::GoalState::aborted);
  EXPECT_THAT(resultOf(*waiting).error_string, ::testing::HasSubstr("stopped"));

  controller->startRequest(Time(now));
  auto again = send(goalTo(1.0, 1.0));
  step();
  ASSERT_EQ(again->state(), servoloop::realtime::GoalState::active);
  controller->stopRequest(Time(now));
  EXPECT_EQ(again->state(), servoloop::realtime::GoalState::preempted);
  EXPECT_THAT(resultOf(*again).error_string, ::testing::HasSubstr("stopped"));
}

TEST_F(ActionTest, UnloadingAbortsTheRunningGoal) {
  auto goal = send(goalTo(1.0, 1.0));
  step();
  ASSERT_EQ(goal->state(), servoloop::realtime::GoalState::active);
  controller.reset();
  EXPECT_EQ(goal->state(), servoloop::realtime::GoalState::aborted);
  EXPECT_THAT(resultOf(*goal).error_string, ::testing::HasSubstr("unloaded"));
}

TEST(JointTrajectoryController, TrajectoriesWhollyInThePastAreRefusedWithAWarningNamingBothTimes) {
  servoloop::test::LogCapture log;
  Fixture<PositionJointTrajectoryController> f(kPositionParams);
  f.start();
  f.runUntil(1.0);
  // Stamped in the past, and (stamp 0: on arrival) with no point after 0.
  f.send(trajectoryMsg({"rev", "cont"}, {pointMsg({0.5, 0.0}, 0.2)}, 0.5));
  EXPECT_EQ(log.count("every point is in the past: the trajectory ends at 0.700000 s and the control time is 1.000000 s"),
            1u);
  f.send(trajectoryMsg({"rev", "cont"}, {pointMsg({0.5, 0.0}, -0.2), pointMsg({0.6, 0.0}, 0.0)}));
  EXPECT_EQ(log.count("every point is in the past"), 2u);
  EXPECT_EQ(f.controller.follower().trajectoriesRefused(), 2u);

  // Checked while its last point was ahead, but it went by before the
  // control thread took it: dropped with the same warning (logged on the
  // bus's delivery thread).
  f.send(trajectoryMsg({"rev", "cont"}, {pointMsg({0.5, 0.0}, 0.5)}, f.now + 0.0005 - 0.5));
  f.step();
  EXPECT_EQ(f.controller.follower().trajectoriesInThePast(), 1u);
  EXPECT_FALSE(f.controller.follower().following());
  f.bus.flush();
  EXPECT_EQ(log.count("every point is in the past"), 3u);
}

}  // namespace
}  // namespace servoloop::controllers::joint_trajectory_controller
