// Angle arithmetic and the per-joint-type position error, against hand values.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "controller_test_support.hpp"
#include "servoloop/controllers/common/angles.hpp"
#include "servoloop/controllers/common/joint_position_error.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::controllers {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(Angles, WrapToPiIsHalfOpenAtMinusPi) {
  EXPECT_DOUBLE_EQ(wrapToPi(kPi), kPi);
  EXPECT_DOUBLE_EQ(wrapToPi(-kPi), kPi);
  EXPECT_DOUBLE_EQ(wrapToPi(3.0 * kPi), kPi);
  EXPECT_NEAR(wrapToPi(1.5 * kPi), -0.5 * kPi, 1e-12);
  EXPECT_NEAR(wrapToPi(-1.5 * kPi), 0.5 * kPi, 1e-12);
  EXPECT_DOUBLE_EQ(wrapToPi(0.25), 0.25);
  EXPECT_NEAR(wrapToPi(6.0), 6.0 - 2.0 * kPi, 1e-12);
}

TEST(Angles, ShortestAngularDistanceGoesTheShortWayRound) {
  // From -3 to 3 the short way passes through ±π: a turn of 6 - 2π (negative).
  EXPECT_NEAR(shortestAngularDistance(-3.0, 3.0), 6.0 - 2.0 * kPi, 1e-12);
  EXPECT_NEAR(shortestAngularDistance(3.0, -3.0), 2.0 * kPi - 6.0, 1e-12);
  EXPECT_NEAR(shortestAngularDistance(0.5, 1.0), 0.5, 1e-12);
}

TEST(Angles, WithinLimitsNeverPassesALimit) {
  // Range [0, 2] (narrower than a turn): only the direct way stays inside.
  EXPECT_NEAR(shortestAngularDistanceWithinLimits(0.1, 1.9, 0.0, 2.0), 1.8, 1e-12);
  // Range [-3.1, 3.1]: from 3 to -3 the short way (through π) crosses the limit,
  // so the long way round it is.
  EXPECT_NEAR(shortestAngularDistanceWithinLimits(3.0, -3.0, -3.1, 3.1), -6.0, 1e-12);
  // Range [-4, 4] holds the target -3 also as -3 + 2π = 3.283..: the short way is allowed.
  EXPECT_NEAR(shortestAngularDistanceWithinLimits(3.0, -3.0, -4.0, 4.0), 2.0 * kPi - 6.0, 1e-12);
  // A target outside the limits: the plain difference.
  EXPECT_NEAR(shortestAngularDistanceWithinLimits(1.0, 2.5, 0.0, 2.0), 1.5, 1e-12);
}

TEST(JointPositionErrorTest, ByJointTypeFromTheUrdf) {
  const auto model = testing::testRobotModel();

  const auto revolute = JointPositionError::fromModel(*model, "rev", "c");
  EXPECT_EQ(revolute.kind(), JointPositionError::Kind::revolute);
  EXPECT_DOUBLE_EQ(revolute.clampSetpoint(3.0), 2.0);
  EXPECT_DOUBLE_EQ(revolute.clampSetpoint(-1.0), 0.0);
  EXPECT_DOUBLE_EQ(revolute.clampSetpoint(1.25), 1.25);
  EXPECT_NEAR(revolute.error(2.0, 1.0), 1.0, 1e-12);

  const auto continuous = JointPositionError::fromModel(*model, "cont", "c");
  EXPECT_EQ(continuous.kind(), JointPositionError::Kind::continuous);
  EXPECT_DOUBLE_EQ(continuous.clampSetpoint(100.0), 100.0);  // no clamping
  EXPECT_NEAR(continuous.error(3.0, -3.0), 6.0 - 2.0 * kPi, 1e-12);

  const auto prismatic = JointPositionError::fromModel(*model, "slide", "c");
  EXPECT_EQ(prismatic.kind(), JointPositionError::Kind::prismatic);
  EXPECT_DOUBLE_EQ(prismatic.clampSetpoint(0.8), 0.5);
  EXPECT_DOUBLE_EQ(prismatic.error(0.5, -3.0), 3.5);  // no wrapping for lengths

  const auto wide = JointPositionError::fromModel(*model, "wide", "c");
  EXPECT_NEAR(wide.error(-3.0, 3.0), 2.0 * kPi - 6.0, 1e-12);
}

TEST(JointPositionErrorTest, RevoluteErrorAgreesWithTheLimitAwareDistanceEverywhere) {
  // "rev" spans [0, 2] (less than a turn) and "wide" more than a turn; the
  // error takes a shortcut when no wrapping can apply. Over a grid of setpoints
  // and positions inside, at and outside the limits (and past ±π), it must
  // equal the limit-aware shortest distance to the clamped setpoint exactly.
  const auto model = testing::testRobotModel();
  for (const char* joint : {"rev", "wide"}) {
    const auto error = JointPositionError::fromModel(*model, joint, "c");
    for (int i = -40; i <= 40; ++i) {
      for (int k = -40; k <= 40; ++k) {
        const double setpoint = error.clampSetpoint(0.1 * i + 0.013);
        const double position = 0.1 * k - 0.007;
        const double expected = shortestAngularDistanceWithinLimits(position, setpoint, error.lowerLimit(),
                                                                    error.upperLimit());
        ASSERT_EQ(error.error(setpoint, position), expected) << joint << " setpoint " << setpoint
                                                             << " position " << position;
      }
    }
    // At the limits themselves.
    EXPECT_EQ(error.error(error.upperLimit(), error.lowerLimit()),
              shortestAngularDistanceWithinLimits(error.lowerLimit(), error.upperLimit(), error.lowerLimit(),
                                                  error.upperLimit()));
  }
  // A narrow joint's error is the plain difference while both are inside.
  const auto narrow = JointPositionError::fromModel(*model, "rev", "c");
  EXPECT_EQ(narrow.error(1.9, 0.1), 1.9 - 0.1);
}

TEST(JointPositionErrorTest, UnknownJointNamesControllerAndJoint) {
  const auto model = testing::testRobotModel();
  try {
    JointPositionError::fromModel(*model, "elbow", "arm_controller");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("arm_controller"), std::string::npos) << message;
    EXPECT_NE(message.find("'elbow'"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace servoloop::controllers
