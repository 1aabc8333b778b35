// compareTrajectories (servoloop compare's arithmetic) on trajectories small
// enough to work out by hand, and requireBackend's messages.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "compare_run.hpp"
#include "compare_trajectory.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::cli {
namespace {

// Two joints, positions and velocities given per sample as {a, b} pairs.
JointTrajectory makeTrajectory(const std::vector<double>& times, const std::vector<std::vector<double>>& positions,
                               const std::vector<std::vector<double>>& velocities,
                               const std::vector<std::string>& joints = {"j1", "j2"}) {
  JointTrajectory trajectory;
  trajectory.topic = "/arm/joint_states";
  for (std::size_t i = 0; i < times.size(); ++i) trajectory.append(times[i], joints, positions[i], velocities[i]);
  return trajectory;
}

TEST(CompareTrajectories, SameStampsGiveMaxTimeSignAndRms) {
  const JointTrajectory a = makeTrajectory({0.0, 0.02, 0.04, 0.06}, {{0, 0}, {1, 0}, {2, 0}, {3, 0}},
                                           {{0, 0}, {0, 0}, {0, 0}, {0, 0}});
  // j1 differs by 0, +0.1, −0.3, +0.2; j2 by 0, 0, 0, 0.5; velocities of j1 by 1 at 0.04.
  const JointTrajectory b = makeTrajectory({0.0, 0.02, 0.04, 0.06}, {{0, 0}, {1.1, 0}, {1.7, 0}, {3.2, 0.5}},
                                           {{0, 0}, {0, 0}, {1, 0}, {0, 0}});
  const TopicComparison c = compareTrajectories(a, b);
  EXPECT_EQ(c.topic, "/arm/joint_states");
  EXPECT_EQ(c.samples, 4u);
  EXPECT_DOUBLE_EQ(c.start_time_s, 0.0);
  EXPECT_DOUBLE_EQ(c.end_time_s, 0.06);
  EXPECT_EQ(c.max_stamp_offset_s, 0.0);
  ASSERT_EQ(c.joints.size(), 2u);
  const JointDifference& j1 = c.joints[0];
  EXPECT_EQ(j1.joint, "j1");
  EXPECT_NEAR(j1.max_position_difference, 0.3, 1e-12);
  EXPECT_NEAR(j1.max_position_signed, -0.3, 1e-12);
  EXPECT_DOUBLE_EQ(j1.max_position_time_s, 0.04);
  // sqrt((0 + 0.01 + 0.09 + 0.04) / 4)
  EXPECT_NEAR(j1.rms_position_difference, std::sqrt(0.14 / 4.0), 1e-12);
  EXPECT_NEAR(j1.max_velocity_difference, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(j1.max_velocity_time_s, 0.04);
  EXPECT_NEAR(j1.rms_velocity_difference, 0.5, 1e-12);  // sqrt(1 / 4)
  EXPECT_DOUBLE_EQ(j1.final_position_a, 3.0);
  EXPECT_DOUBLE_EQ(j1.final_position_b, 3.2);
  EXPECT_NEAR(c.joints[1].max_position_difference, 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(c.joints[1].max_position_time_s, 0.06);
  ASSERT_EQ(c.position_difference.size(), 2u);
  EXPECT_NEAR(c.position_difference[0][2], -0.3, 1e-12);
}

TEST(CompareTrajectories, OffsetStampsInterpolateTheSecondRunInsideItsSpan) {
  // A every 0.01 s from 0 to 0.05; B every 0.02 s from 0.01 to 0.05 with q = 10 t
  // (linear, so interpolation is exact), A with q = 10 t + 0.05.
  std::vector<double> ta, tb;
  std::vector<std::vector<double>> qa, qb, zero_a, zero_b;
  for (int i = 0; i <= 5; ++i) {
    ta.push_back(0.01 * i);
    qa.push_back({10 * 0.01 * i + 0.05});
    zero_a.push_back({0.0});
  }
  for (double t : {0.01, 0.03, 0.05}) {
    tb.push_back(t);
    qb.push_back({10 * t});
    zero_b.push_back({0.0});
  }
  const JointTrajectory a = makeTrajectory(ta, qa, zero_a, {"j1"});
  const JointTrajectory b = makeTrajectory(tb, qb, zero_b, {"j1"});
  const TopicComparison c = compareTrajectories(a, b);
  EXPECT_EQ(c.samples, 5u);  // 0.01 .. 0.05; t = 0 is before B starts
  EXPECT_DOUBLE_EQ(c.start_time_s, 0.01);
  EXPECT_NEAR(c.max_stamp_offset_s, 0.01, 1e-12);
  EXPECT_NEAR(c.joints[0].max_position_difference, 0.05, 1e-12);
  EXPECT_NEAR(c.joints[0].rms_position_difference, 0.05, 1e-12);
}

TEST(CompareTrajectories, JointsMatchByNameAndOrder) {
  const JointTrajectory a = makeTrajectory({0.0}, {{1.0, 2.0}}, {{0, 0}}, {"j1", "j2"});
  const JointTrajectory b = makeTrajectory({0.0}, {{2.5, 1.0}}, {{0, 0}}, {"j2", "j1"});
  const TopicComparison c = compareTrajectories(a, b);
  ASSERT_EQ(c.joints.size(), 2u);
  EXPECT_EQ(c.joints[0].joint, "j1");
  EXPECT_DOUBLE_EQ(c.joints[0].max_position_difference, 0.0);
  EXPECT_DOUBLE_EQ(c.joints[1].max_position_difference, 0.5);
}

TEST(JointTrajectory, TwoPublishersInterleavedAreSortedWithOneSamplePerStamp) {
  // A 50 Hz and a 100 Hz publisher of the same state, delivered publisher by publisher.
  JointTrajectory t = makeTrajectory({0.0, 0.02, 0.0, 0.01, 0.02, 0.03}, {{0}, {2}, {0}, {1}, {2}, {3}},
                                     {{0}, {0}, {0}, {0}, {0}, {0}}, {"j1"});
  t.sortByStamp();
  EXPECT_EQ(t.time_s, (std::vector<double>{0.0, 0.01, 0.02, 0.03}));
  EXPECT_EQ(t.position[0], (std::vector<double>{0, 1, 2, 3}));
}

TEST(CompareTrajectories, DivergedRunCountsAsInfinite) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const JointTrajectory a = makeTrajectory({0.0, 0.1, 0.2}, {{0}, {0}, {0}}, {{0}, {0}, {0}}, {"j1"});
  const JointTrajectory b = makeTrajectory({0.0, 0.1, 0.2}, {{0}, {nan}, {1e3}}, {{0}, {0}, {0}}, {"j1"});
  const TopicComparison c = compareTrajectories(a, b);
  EXPECT_TRUE(std::isinf(c.joints[0].max_position_difference));
  EXPECT_DOUBLE_EQ(c.joints[0].max_position_time_s, 0.1);
}

TEST(CompareTrajectories, ErrorsNameTheTopic) {
  const JointTrajectory a = makeTrajectory({0.0, 1.0}, {{0}, {0}}, {{0}, {0}}, {"j1"});
  JointTrajectory empty;
  empty.topic = "/arm/joint_states";
  const auto message = [](const JointTrajectory& x, const JointTrajectory& y) {
    try {
      compareTrajectories(x, y);
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(a, empty).find("topic '/arm/joint_states': the second run recorded no message"),
            std::string::npos);
  const JointTrajectory other_joint = makeTrajectory({0.0}, {{0}}, {{0}}, {"k1"});
  EXPECT_NE(message(a, other_joint).find("share no joint name"), std::string::npos);
  const JointTrajectory later = makeTrajectory({5.0, 6.0}, {{0}, {0}}, {{0}, {0}}, {"j1"});
  EXPECT_NE(message(a, later).find("do not overlap in time"), std::string::npos);
}

TEST(RequireBackend, ListsTheAvailableOnesAndExplainsAMissingMujoco) {
  EXPECT_NO_THROW(requireBackend("mock", {"bullet", "mock"}));
  try {
    requireBackend("warp", {"bullet", "mock"});
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(), "unknown backend 'warp'; available backends: bullet, mock");
  }
  try {
    requireBackend("mujoco", {"bullet", "mock"});
    FAIL() << "no error";
  } catch (const Error& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("backend 'mujoco' is not available: this servoloop was built without MuJoCo"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("libmujoco-dev"), std::string::npos) << what;
    EXPECT_NE(what.find("available backends: bullet, mock"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace servoloop::cli
