// The joint trajectory built from points, against hand values and against
// its own splines' references: points in the past dropped, the first segment
// from the current state, a replacement mid-segment continuous in position,
// velocity and acceleration, continuous joints the short way round.
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "servoloop/controllers/common/joint_trajectory.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::controllers {
namespace {

TrajectoryPoint point(std::vector<double> positions, double time_from_start, std::vector<double> velocities = {},
                      std::vector<double> accelerations = {}) {
  return {std::move(positions), std::move(velocities), std::move(accelerations), time_from_start};
}

// fromPoints() then activate() at now, as a controller does (start time 0: now).
JointTrajectory build(double now, double start_time, const std::vector<JointSample>& current,
                      const std::vector<TrajectoryPoint>& points, const std::vector<bool>& continuous = {}) {
  JointTrajectory trajectory =
      JointTrajectory::fromPoints(start_time > 0.0 ? start_time : now, points, current.size(), continuous);
  EXPECT_TRUE(trajectory.activate(now, current));
  return trajectory;
}

TEST(JointTrajectory, LinearThroughPositionsFromTheCurrentState) {
  // Now = 1 s, start now: points at 1.5 s and 2.5 s.
  const auto trajectory = build(1.0, 0.0, {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}},
                                                 {point({1.0, 1.0}, 0.5), point({3.0, 0.0}, 1.5)});
  ASSERT_EQ(trajectory.pointCount(), 2u);
  EXPECT_EQ(trajectory.droppedPoints(), 0u);
  EXPECT_DOUBLE_EQ(trajectory.endTime(), 2.5);
  std::vector<JointSample> out(2);
  trajectory.sample(1.25, out);  // half way to the first point
  EXPECT_NEAR(out[0].position, 0.5, 1e-12);
  EXPECT_NEAR(out[0].velocity, 2.0, 1e-12);
  EXPECT_NEAR(out[1].position, 1.0, 1e-12);
  trajectory.sample(2.0, out);  // half way between the points
  EXPECT_NEAR(out[0].position, 2.0, 1e-12);
  EXPECT_NEAR(out[0].velocity, 2.0, 1e-12);
  EXPECT_NEAR(out[1].position, 0.5, 1e-12);
  EXPECT_NEAR(out[1].velocity, -1.0, 1e-12);
  trajectory.sample(9.0, out);  // after the end: the last point, at rest
  EXPECT_DOUBLE_EQ(out[0].position, 3.0);
  EXPECT_EQ(out[0].velocity, 0.0);
  trajectory.sample(0.5, out);  // before now: the current position, at rest
  EXPECT_DOUBLE_EQ(out[0].position, 0.0);
  EXPECT_EQ(out[0].velocity, 0.0);
}

TEST(JointTrajectory, PointsNotAfterNowAreDropped) {
  // Started at 1 s, now 2 s: the point at 1.5 s is history.
  const auto trajectory = build(2.0, 1.0, {{0.0, 0.0, 0.0}},
                                                 {point({5.0}, 0.5), point({1.0}, 1.5), point({2.0}, 2.5)});
  EXPECT_EQ(trajectory.droppedPoints(), 1u);
  std::vector<JointSample> out(1);
  trajectory.sample(2.25, out);  // from the current state at 2 s to 1.0 at 2.5 s
  EXPECT_NEAR(out[0].position, 0.5, 1e-12);

  // Every point in the past: activation refuses it and changes nothing.
  auto past = JointTrajectory::fromPoints(1.0, {point({5.0}, 0.5), point({1.0}, 9.0)}, 1);
  EXPECT_FALSE(past.activate(10.0, {{0.0, 0.0, 0.0}}));
}

TEST(JointTrajectory, JointsNotInAPartialTrajectoryHoldWhereTheyAre) {
  auto trajectory = JointTrajectory::fromPoints(0.0, {point({2.0, 99.0}, 1.0)}, 2, {}, {false, true});
  ASSERT_TRUE(trajectory.activate(0.0, {{0.0, 0.0, 0.0}, {0.4, 0.3, 0.0}}));
  std::vector<JointSample> out(2);
  trajectory.sample(0.5, out);
  EXPECT_NEAR(out[0].position, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(out[1].position, 0.4);
  EXPECT_EQ(out[1].velocity, 0.0);
}

// A new trajectory built from the old one's state at the moment of
// replacement continues it without a jump in position, velocity or (for a
// quintic) acceleration.
TEST(JointTrajectory, ReplacementMidSegmentIsContinuous) {
  const auto first = build(0.0, 0.0, {{0.0, 0.0, 0.0}},
                                            {point({1.0}, 1.0, {0.5}, {0.0}), point({0.0}, 2.0, {0.0}, {0.0})});
  std::vector<JointSample> at_switch(1);
  first.sample(0.7, at_switch);
  ASSERT_GT(std::abs(at_switch[0].velocity), 0.1);  // really mid-motion

  const auto second = build(0.7, 0.0, at_switch, {point({-1.0}, 0.8, {0.0}, {0.0})});
  std::vector<JointSample> just_after(1);
  second.sample(0.7, just_after);
  EXPECT_NEAR(just_after[0].position, at_switch[0].position, 1e-12);
  EXPECT_NEAR(just_after[0].velocity, at_switch[0].velocity, 1e-12);
  EXPECT_NEAR(just_after[0].acceleration, at_switch[0].acceleration, 1e-9);
  second.sample(0.7 + 1e-6, just_after);
  EXPECT_NEAR(just_after[0].position, at_switch[0].position + 1e-6 * at_switch[0].velocity, 1e-9);
}

TEST(JointTrajectory, ContinuousJointsGoTheShortWayRound) {
  const double two_pi = 2.0 * std::numbers::pi;
  // From 3.0 rad to -3.0 rad: 0.28 rad forward across ±π, not 6 rad back.
  const auto trajectory = build(0.0, 0.0, {{3.0, 0.0, 0.0}, {3.0, 0.0, 0.0}},
                                                 {point({-3.0, -3.0}, 1.0), point({-2.5, -2.5}, 2.0)}, {true, false});
  std::vector<JointSample> out(2);
  trajectory.sample(0.5, out);
  EXPECT_NEAR(out[0].velocity, -3.0 + two_pi - 3.0, 1e-12);  // +0.283 rad/s
  EXPECT_NEAR(out[1].velocity, -6.0, 1e-12);                 // a revolute joint takes the way it is given
  trajectory.sample(2.0, out);
  EXPECT_NEAR(out[0].position, -2.5 + two_pi, 1e-12);  // the later points keep their differences
  EXPECT_NEAR(out[1].position, -2.5, 1e-12);
}

TEST(JointTrajectory, QuinticFromRestToRestIsTheMinimumJerkProfile) {
  const auto trajectory =
      build(3.0, 0.0, {{1.0, 0.0, 0.0}}, {point({3.0}, 2.0, {0.0}, {0.0})});
  std::vector<JointSample> out(1);
  trajectory.sample(4.0, out);  // half way in time: half way in position, peak speed 1.875 * 2 / 2
  EXPECT_NEAR(out[0].position, 2.0, 1e-12);
  EXPECT_NEAR(out[0].velocity, 1.875, 1e-12);
  EXPECT_NEAR(out[0].acceleration, 0.0, 1e-12);
}

TEST(JointTrajectory, MalformedPointsAreErrorsNamingThePoint) {
  const std::vector<JointSample> current(2);
  const auto error = [&](const std::vector<TrajectoryPoint>& points) -> std::string {
    try {
      JointTrajectory::fromPoints(0.0, points, current.size());
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(error({point({1.0}, 1.0)}).find("point 0: positions has 1 values for 2 joints"), std::string::npos);
  EXPECT_NE(error({point({1.0, NAN}, 1.0)}).find("positions[1] is not a finite number"), std::string::npos);
  EXPECT_NE(error({point({1.0, 1.0}, 1.0), point({1.0, 2.0}, 1.0)}).find("point 1: time_from_start"),
            std::string::npos);
  EXPECT_NE(error({point({1.0, 1.0}, 1.0, {}, {0.0, 0.0})}).find("accelerations without velocities"),
            std::string::npos);
  EXPECT_NE(error({point({1.0, 1.0}, 1.0, {0.0})}).find("velocities has 1 values"), std::string::npos);
}

}  // namespace
}  // namespace servoloop::controllers
