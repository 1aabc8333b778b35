// Joint limits enforcement (ros_control_semantics.md "Joint limits"), each rule
// with hand-calculated numbers, boundaries and NaN commands.
//
// Unless a test says otherwise the joint is the seed's joint1: position [0, 2],
// velocity 0.5, effort 10; soft limits [0.1, 1.9] with k_position 10,
// k_velocity 2.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/interface_manager.hpp"
#include "servoloop/hardware_interface/joint_limits_interface.hpp"
#include "expect_contains.hpp"

namespace hi = servoloop::hardware_interface;
using servoloop::Duration;

namespace {

constexpr double kTol = 1e-12;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// One joint's storage and its command handle.
struct FakeJoint {
  explicit FakeJoint(const std::string& name = "joint1")
      : handle(hi::JointStateHandle(name, &position, &velocity, &effort), &command) {}
  double position = 1.0;
  double velocity = 0.0;
  double effort = 0.0;
  double command = 0.0;
  hi::JointHandle handle;
};

hi::JointLimits seedLimits() {
  hi::JointLimits limits;
  limits.has_position_limits = true;
  limits.min_position = 0.0;
  limits.max_position = 2.0;
  limits.has_velocity_limits = true;
  limits.max_velocity = 0.5;
  limits.has_effort_limits = true;
  limits.max_effort = 10.0;
  return limits;
}

hi::SoftJointLimits seedSoftLimits() {
  hi::SoftJointLimits soft;
  soft.min_position = 0.1;
  soft.max_position = 1.9;
  soft.k_position = 10.0;
  soft.k_velocity = 2.0;
  return soft;
}

// Writes `command`, enforces, returns what is left.
template <class HandleT>
double limited(HandleT& handle, FakeJoint& joint, double command, double period_s = 0.1) {
  joint.command = command;
  handle.enforceLimits(Duration(period_s));
  return joint.command;
}

template <class F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const servoloop::Error& e) {
    return e.what();
  }
  return "(no servoloop::Error)";
}

}  // namespace

// --- EffortJointSaturationHandle -------------------------------------------------

TEST(EffortJointSaturation, ClampsToMaxEffortInsideTheRange) {
  FakeJoint joint;
  hi::EffortJointSaturationHandle handle(joint.handle, seedLimits());
  EXPECT_EQ(limited(handle, joint, 15.0), 10.0);
  EXPECT_EQ(limited(handle, joint, -15.0), -10.0);
  EXPECT_EQ(limited(handle, joint, 3.0), 3.0);
  EXPECT_EQ(limited(handle, joint, 10.0), 10.0);
  EXPECT_EQ(limited(handle, joint, kInf), 10.0);
}

TEST(EffortJointSaturation, AtThePositionLimitsBothDirectionsAreAllowed) {
  FakeJoint joint;
  hi::EffortJointSaturationHandle handle(joint.handle, seedLimits());
  joint.position = 0.0;  // exactly p_min: not beyond it
  EXPECT_EQ(limited(handle, joint, -15.0), -10.0);
  joint.position = 2.0;  // exactly p_max
  EXPECT_EQ(limited(handle, joint, 15.0), 10.0);
}

TEST(EffortJointSaturation, BeyondAPositionLimitOnlyPushesBack) {
  FakeJoint joint;
  hi::EffortJointSaturationHandle handle(joint.handle, seedLimits());
  joint.position = -0.1;
  EXPECT_EQ(limited(handle, joint, -5.0), 0.0);
  EXPECT_EQ(limited(handle, joint, 5.0), 5.0);
  EXPECT_EQ(limited(handle, joint, 15.0), 10.0);
  joint.position = 2.1;
  EXPECT_EQ(limited(handle, joint, 5.0), 0.0);
  EXPECT_EQ(limited(handle, joint, -5.0), -5.0);
  EXPECT_EQ(limited(handle, joint, -15.0), -10.0);
}

TEST(EffortJointSaturation, FasterThanMaxVelocityOnlyBrakes) {
  FakeJoint joint;
  hi::EffortJointSaturationHandle handle(joint.handle, seedLimits());
  joint.velocity = 0.5;  // exactly v_max: not beyond it
  EXPECT_EQ(limited(handle, joint, 15.0), 10.0);
  joint.velocity = 0.6;
  EXPECT_EQ(limited(handle, joint, 5.0), 0.0);
  EXPECT_EQ(limited(handle, joint, -12.0), -10.0);
  joint.velocity = -0.6;
  EXPECT_EQ(limited(handle, joint, -5.0), 0.0);
  EXPECT_EQ(limited(handle, joint, 4.0), 4.0);
}

TEST(EffortJointSaturation, BelowRangeAndTooFastUpwardsAllowsOnlyZero) {
  FakeJoint joint;
  hi::EffortJointSaturationHandle handle(joint.handle, seedLimits());
  joint.position = -0.1;  // lower bound 0
  joint.velocity = 0.6;   // upper bound 0
  EXPECT_EQ(limited(handle, joint, 5.0), 0.0);
  EXPECT_EQ(limited(handle, joint, -5.0), 0.0);
}

TEST(EffortJointSaturation, NaNCommandBecomesZero) {
  FakeJoint joint;
  hi::EffortJointSaturationHandle handle(joint.handle, seedLimits());
  EXPECT_EQ(limited(handle, joint, kNaN), 0.0);
  joint.position = 2.5;
  EXPECT_EQ(limited(handle, joint, kNaN), 0.0);
}

TEST(EffortJointSaturation, VelocityAndPositionLimitsAreOptional) {
  FakeJoint joint;
  hi::JointLimits limits;
  limits.has_effort_limits = true;
  limits.max_effort = 2.0;
  hi::EffortJointSaturationHandle handle(joint.handle, limits);
  joint.position = 100.0;
  joint.velocity = 100.0;
  EXPECT_EQ(limited(handle, joint, 1.5), 1.5);
  EXPECT_EQ(limited(handle, joint, 3.0), 2.0);
}

TEST(EffortJointSaturation, NeedsAnEffortLimit) {
  FakeJoint joint;
  hi::JointLimits limits = seedLimits();
  limits.has_effort_limits = false;
  const std::string message = errorOf([&] { hi::EffortJointSaturationHandle(joint.handle, limits); });
  EXPECT_CONTAINS(message, "joint 'joint1'");
  EXPECT_CONTAINS(message, "EffortJointSaturationHandle needs an effort limit");
  EXPECT_CONTAINS(message, "max_effort under joint_limits/joint1");
}

TEST(EffortJointSaturation, RefusesAnEmptyHandleAndNegativeMagnitudes) {
  EXPECT_CONTAINS(errorOf([&] { hi::EffortJointSaturationHandle(hi::JointHandle(), seedLimits()); }),
                  "joint handle is empty");
  FakeJoint joint;
  hi::JointLimits limits = seedLimits();
  limits.max_effort = -1.0;
  EXPECT_CONTAINS(errorOf([&] { hi::EffortJointSaturationHandle(joint.handle, limits); }),
                  "max_effort is -1");
}

// --- EffortJointSoftLimitsHandle --------------------------------------------------

TEST(EffortJointSoftLimits, MidRangeAtRest) {
  // p = 1, v = 0: v_lo = clamp(-10·0.9) = -0.5, v_hi = clamp(-10·(-0.9)) = 0.5;
  // e_lo = -2·(0 + 0.5) = -1, e_hi = -2·(0 - 0.5) = 1.
  FakeJoint joint;
  hi::EffortJointSoftLimitsHandle handle(joint.handle, seedLimits(), seedSoftLimits());
  EXPECT_NEAR(limited(handle, joint, 5.0), 1.0, kTol);
  EXPECT_NEAR(limited(handle, joint, -5.0), -1.0, kTol);
  EXPECT_NEAR(limited(handle, joint, 0.3), 0.3, kTol);
}

TEST(EffortJointSoftLimits, NearTheUpperSoftLimitMoving) {
  // p = 1.92, v = 0.2: v_hi = clamp(-10·0.02) = -0.2, v_lo = -0.5;
  // e_lo = -2·(0.2 + 0.5) = -1.4, e_hi = -2·(0.2 + 0.2) = -0.8.
  FakeJoint joint;
  hi::EffortJointSoftLimitsHandle handle(joint.handle, seedLimits(), seedSoftLimits());
  joint.position = 1.92;
  joint.velocity = 0.2;
  EXPECT_NEAR(limited(handle, joint, 5.0), -0.8, kTol);
  EXPECT_NEAR(limited(handle, joint, -5.0), -1.4, kTol);
  EXPECT_NEAR(limited(handle, joint, -1.0), -1.0, kTol);
  // 0 is outside [e_lo, e_hi] here: a NaN command becomes 0, then -0.8.
  EXPECT_NEAR(limited(handle, joint, kNaN), -0.8, kTol);
}

TEST(EffortJointSoftLimits, ExactlyAtTheSoftLimitAtRest) {
  // p = 1.9, v = 0: v_hi = 0, e_hi = 0; v_lo = -0.5, e_lo = -1.
  FakeJoint joint;
  hi::EffortJointSoftLimitsHandle handle(joint.handle, seedLimits(), seedSoftLimits());
  joint.position = 1.9;
  EXPECT_NEAR(limited(handle, joint, 5.0), 0.0, kTol);
  EXPECT_NEAR(limited(handle, joint, -0.5), -0.5, kTol);
  EXPECT_NEAR(limited(handle, joint, -5.0), -1.0, kTol);
}

TEST(EffortJointSoftLimits, EffortBoundsAreClampedToMaxEffort) {
  // k_velocity 100: e_lo = clamp(-100·0.5) = -10, e_hi = 10.
  FakeJoint joint;
  hi::SoftJointLimits soft = seedSoftLimits();
  soft.k_velocity = 100.0;
  hi::EffortJointSoftLimitsHandle handle(joint.handle, seedLimits(), soft);
  EXPECT_NEAR(limited(handle, joint, 15.0), 10.0, kTol);
  EXPECT_NEAR(limited(handle, joint, -15.0), -10.0, kTol);
}

TEST(EffortJointSoftLimits, WithoutPositionLimitsOnlyVelocityDamping) {
  // No hard position limits: v_lo, v_hi = ∓0.5 whatever p; v = 1:
  // e_lo = -2·(1 + 0.5) = -3, e_hi = -2·(1 - 0.5) = -1.
  FakeJoint joint;
  hi::JointLimits limits = seedLimits();
  limits.has_position_limits = false;
  hi::EffortJointSoftLimitsHandle handle(joint.handle, limits, seedSoftLimits());
  joint.position = 50.0;
  joint.velocity = 1.0;
  EXPECT_NEAR(limited(handle, joint, 0.0), -1.0, kTol);
  EXPECT_NEAR(limited(handle, joint, -5.0), -3.0, kTol);
}

TEST(EffortJointSoftLimits, NeedsVelocityAndEffortLimitsAndSaneSoftLimits) {
  FakeJoint joint;
  hi::JointLimits limits = seedLimits();
  limits.has_velocity_limits = false;
  EXPECT_CONTAINS(
      errorOf([&] { hi::EffortJointSoftLimitsHandle(joint.handle, limits, seedSoftLimits()); }),
      "EffortJointSoftLimitsHandle needs a velocity limit");
  limits = seedLimits();
  limits.has_effort_limits = false;
  EXPECT_CONTAINS(
      errorOf([&] { hi::EffortJointSoftLimitsHandle(joint.handle, limits, seedSoftLimits()); }),
      "EffortJointSoftLimitsHandle needs an effort limit");
  hi::SoftJointLimits soft = seedSoftLimits();
  std::swap(soft.min_position, soft.max_position);
  EXPECT_CONTAINS(errorOf([&] { hi::EffortJointSoftLimitsHandle(joint.handle, seedLimits(), soft); }),
                  "joint 'joint1': soft_lower_limit 1.9 is above soft_upper_limit 0.1");
}

// --- PositionJointSaturationHandle ------------------------------------------------

TEST(PositionJointSaturation, RateLimitedAroundThePreviousCommand) {
  // v_max·dt = 0.5·0.1 = 0.05; the first previous command is the measured 1.0.
  FakeJoint joint;
  hi::PositionJointSaturationHandle handle(joint.handle, seedLimits());
  EXPECT_NEAR(limited(handle, joint, 1.2), 1.05, kTol);
  EXPECT_NEAR(limited(handle, joint, 1.2), 1.10, kTol);
  EXPECT_NEAR(limited(handle, joint, 0.0), 1.05, kTol);
  EXPECT_NEAR(limited(handle, joint, 1.07), 1.07, kTol);
}

TEST(PositionJointSaturation, StopsExactlyAtThePositionLimit) {
  FakeJoint joint;
  joint.position = 1.98;
  hi::PositionJointSaturationHandle handle(joint.handle, seedLimits());
  EXPECT_EQ(limited(handle, joint, 2.5), 2.0);  // [1.93, min(2.03, 2)]
  EXPECT_EQ(limited(handle, joint, 2.5), 2.0);  // [1.95, 2]
  EXPECT_NEAR(limited(handle, joint, 0.0), 1.95, kTol);
}

TEST(PositionJointSaturation, StartingBeyondALimitJumpsToIt) {
  // Measured 2.1: rate bounds [2.05, 2.15] cross the limit 2; the limit wins.
  FakeJoint joint;
  joint.position = 2.1;
  hi::PositionJointSaturationHandle handle(joint.handle, seedLimits());
  EXPECT_EQ(limited(handle, joint, 2.1), 2.0);
}

TEST(PositionJointSaturation, WithoutVelocityLimitOnlyTheRange) {
  FakeJoint joint;
  hi::JointLimits limits = seedLimits();
  limits.has_velocity_limits = false;
  hi::PositionJointSaturationHandle handle(joint.handle, limits);
  EXPECT_EQ(limited(handle, joint, 3.0), 2.0);
  EXPECT_EQ(limited(handle, joint, -1.0), 0.0);
  EXPECT_EQ(limited(handle, joint, 0.0), 0.0);
  EXPECT_EQ(limited(handle, joint, 1.5), 1.5);
}

TEST(PositionJointSaturation, WithoutPositionLimitsOnlyTheRate) {
  FakeJoint joint;
  joint.position = 10.0;
  hi::JointLimits limits = seedLimits();
  limits.has_position_limits = false;
  hi::PositionJointSaturationHandle handle(joint.handle, limits);
  EXPECT_NEAR(limited(handle, joint, 20.0), 10.05, kTol);
}

TEST(PositionJointSaturation, NaNCommandHoldsThePreviousCommand) {
  FakeJoint joint;
  hi::PositionJointSaturationHandle handle(joint.handle, seedLimits());
  EXPECT_NEAR(limited(handle, joint, kNaN), 1.0, kTol);  // first: the measured position
  EXPECT_NEAR(limited(handle, joint, 1.03), 1.03, kTol);
  EXPECT_NEAR(limited(handle, joint, kNaN), 1.03, kTol);
}

TEST(PositionJointSaturation, ZeroPeriodHoldsAndResetRestartsFromMeasured) {
  FakeJoint joint;
  hi::PositionJointSaturationHandle handle(joint.handle, seedLimits());
  EXPECT_NEAR(limited(handle, joint, 1.2), 1.05, kTol);
  EXPECT_NEAR(limited(handle, joint, 1.2, 0.0), 1.05, kTol);
  joint.position = 0.5;
  handle.reset();
  EXPECT_NEAR(limited(handle, joint, 1.0), 0.55, kTol);
}

TEST(PositionJointSaturation, NeedsPositionOrVelocityLimits) {
  FakeJoint joint;
  const std::string message =
      errorOf([&] { hi::PositionJointSaturationHandle(joint.handle, hi::JointLimits{}); });
  EXPECT_CONTAINS(message, "joint 'joint1': PositionJointSaturationHandle needs position or velocity");
}

// --- VelocityJointSaturationHandle ------------------------------------------------

TEST(VelocityJointSaturation, ClampsToMaxVelocity) {
  FakeJoint joint;
  hi::VelocityJointSaturationHandle handle(joint.handle, seedLimits());
  EXPECT_EQ(limited(handle, joint, 0.7), 0.5);
  EXPECT_EQ(limited(handle, joint, -0.5), -0.5);  // exactly -v_max
  EXPECT_EQ(limited(handle, joint, -0.9), -0.5);
  EXPECT_EQ(limited(handle, joint, 0.3), 0.3);
  EXPECT_EQ(limited(handle, joint, kNaN), 0.0);
}

TEST(VelocityJointSaturation, AccelerationLimitAroundThePreviousCommand) {
  // a_max·dt = 2·0.1 = 0.2; the first previous command is the measured 0.1.
  FakeJoint joint;
  joint.velocity = 0.1;
  hi::JointLimits limits = seedLimits();
  limits.has_acceleration_limits = true;
  limits.max_acceleration = 2.0;
  hi::VelocityJointSaturationHandle handle(joint.handle, limits);
  EXPECT_NEAR(limited(handle, joint, 0.5), 0.3, kTol);   // [-0.1, 0.3]
  EXPECT_NEAR(limited(handle, joint, 0.5), 0.5, kTol);   // [0.1, min(0.7, 0.5)]
  EXPECT_NEAR(limited(handle, joint, -0.5), 0.3, kTol);  // [0.3, 0.5]
  EXPECT_NEAR(limited(handle, joint, kNaN), 0.1, kTol);  // 0 clamped into [0.1, 0.5]

  joint.velocity = -0.4;
  handle.reset();
  EXPECT_NEAR(limited(handle, joint, 0.5), -0.2, kTol);  // [max(-0.6, -0.5), -0.2]
}

TEST(VelocityJointSaturation, NeedsAVelocityLimit) {
  FakeJoint joint("wheel");
  hi::JointLimits limits = seedLimits();
  limits.has_velocity_limits = false;
  const std::string message = errorOf([&] { hi::VelocityJointSaturationHandle(joint.handle, limits); });
  EXPECT_CONTAINS(message, "joint 'wheel': VelocityJointSaturationHandle needs a velocity limit");
  EXPECT_CONTAINS(message, "velocity=\"…\"");
}

// --- PositionJointSoftLimitsHandle ------------------------------------------------

TEST(PositionJointSoftLimits, FarFromTheSoftLimitsOnlyTheRate) {
  // prev 1.0: v_lo = clamp(-9) = -0.5, v_hi = clamp(9) = 0.5 → [0.95, 1.05].
  FakeJoint joint;
  hi::PositionJointSoftLimitsHandle handle(joint.handle, seedLimits(), seedSoftLimits());
  EXPECT_NEAR(limited(handle, joint, 1.5), 1.05, kTol);
}

TEST(PositionJointSoftLimits, ApproachesTheSoftLimitAndStopsThere) {
  // prev 1.88: v_hi = clamp(-10·(-0.02)) = 0.2 → upper 1.88 + 0.02 = 1.9.
  // prev 1.9: v_hi = 0 → upper 1.9.
  FakeJoint joint;
  joint.position = 1.88;
  hi::PositionJointSoftLimitsHandle handle(joint.handle, seedLimits(), seedSoftLimits());
  EXPECT_NEAR(limited(handle, joint, 2.0), 1.9, kTol);
  EXPECT_NEAR(limited(handle, joint, 2.0), 1.9, kTol);
  EXPECT_NEAR(limited(handle, joint, 1.5), 1.85, kTol);  // v_lo = -0.5 → 1.9 - 0.05
}

TEST(PositionJointSoftLimits, BeyondTheSoftLimitPullsBack) {
  // prev = measured 1.95: v_hi = clamp(-0.5) = -0.5, v_lo = -0.5 → [1.9, 1.9].
  FakeJoint joint;
  joint.position = 1.95;
  hi::PositionJointSoftLimitsHandle handle(joint.handle, seedLimits(), seedSoftLimits());
  EXPECT_NEAR(limited(handle, joint, 2.0), 1.9, kTol);
  // NaN holds prev 1.9, inside [1.9 - 0.05, 1.9 + 0].
  EXPECT_NEAR(limited(handle, joint, kNaN), 1.9, kTol);
}

TEST(PositionJointSoftLimits, NeedsAVelocityLimit) {
  FakeJoint joint;
  hi::JointLimits limits = seedLimits();
  limits.has_velocity_limits = false;
  EXPECT_CONTAINS(
      errorOf([&] { hi::PositionJointSoftLimitsHandle(joint.handle, limits, seedSoftLimits()); }),
      "PositionJointSoftLimitsHandle needs a velocity limit");
}

// --- VelocityJointSoftLimitsHandle ------------------------------------------------

TEST(VelocityJointSoftLimits, BoundsShrinkNearTheSoftLimit) {
  // p = 1.88: v_hi = clamp(0.2) = 0.2, v_lo = clamp(-17.8) = -0.5.
  FakeJoint joint;
  joint.position = 1.88;
  hi::VelocityJointSoftLimitsHandle handle(joint.handle, seedLimits(), seedSoftLimits());
  EXPECT_NEAR(limited(handle, joint, 0.4), 0.2, kTol);
  EXPECT_NEAR(limited(handle, joint, -0.7), -0.5, kTol);
  // p = 1.95: v_lo = v_hi = -0.5; even a NaN (0) command becomes -0.5.
  joint.position = 1.95;
  EXPECT_NEAR(limited(handle, joint, 0.0), -0.5, kTol);
  EXPECT_NEAR(limited(handle, joint, kNaN), -0.5, kTol);
}

TEST(VelocityJointSoftLimits, AccelerationLimitAroundTheMeasuredVelocity) {
  // p = 1, v = 0, a_max·dt = 0.2 → [-0.2, 0.2].
  FakeJoint joint;
  hi::JointLimits limits = seedLimits();
  limits.has_acceleration_limits = true;
  limits.max_acceleration = 2.0;
  hi::VelocityJointSoftLimitsHandle handle(joint.handle, limits, seedSoftLimits());
  EXPECT_NEAR(limited(handle, joint, 0.4), 0.2, kTol);
  EXPECT_NEAR(limited(handle, joint, -0.4), -0.2, kTol);
}

// --- JointLimitsInterface ---------------------------------------------------------

TEST(JointLimitsInterface, EnforcesEveryJointInOneCall) {
  FakeJoint joint1("joint1");
  FakeJoint joint2("joint2");
  hi::JointLimits small = seedLimits();
  small.max_effort = 1.0;
  hi::EffortJointSaturationInterface limits_interface;
  limits_interface.registerHandle(hi::EffortJointSaturationHandle(joint1.handle, seedLimits()));
  limits_interface.registerHandle(hi::EffortJointSaturationHandle(joint2.handle, small));
  EXPECT_EQ(limits_interface.size(), 2u);
  EXPECT_STREQ(limits_interface.name(), "EffortJointSaturationInterface");

  joint1.command = 20.0;
  joint2.command = -20.0;
  limits_interface.enforceLimits(Duration(0.01));
  EXPECT_EQ(joint1.command, 10.0);
  EXPECT_EQ(joint2.command, -1.0);

  // Registering joint2 again replaces its handle.
  limits_interface.registerHandle(hi::EffortJointSaturationHandle(joint2.handle, seedLimits()));
  EXPECT_EQ(limits_interface.size(), 2u);
  joint2.command = -20.0;
  limits_interface.enforceLimits(Duration(0.01));
  EXPECT_EQ(joint2.command, -10.0);
  EXPECT_TRUE(limits_interface.hasHandle("joint2"));
  EXPECT_EQ(limits_interface.getHandle("joint2").getName(), "joint2");
  limits_interface.reset();  // stateless handles: a no-op that compiles
}

TEST(JointLimitsInterface, ResetForgetsPreviousCommands) {
  FakeJoint joint;
  hi::PositionJointSaturationInterface limits_interface;
  limits_interface.registerHandle(hi::PositionJointSaturationHandle(joint.handle, seedLimits()));
  joint.command = 1.2;
  limits_interface.enforceLimits(Duration(0.1));
  EXPECT_NEAR(joint.command, 1.05, kTol);
  joint.position = 0.5;
  limits_interface.reset();
  joint.command = 1.2;
  limits_interface.enforceLimits(Duration(0.1));
  EXPECT_NEAR(joint.command, 0.55, kTol);
}

TEST(JointLimitsInterface, UnknownJointAndRegistrationWithARobot) {
  FakeJoint joint;
  hi::VelocityJointSaturationInterface limits_interface;
  limits_interface.registerHandle(hi::VelocityJointSaturationHandle(joint.handle, seedLimits()));
  try {
    limits_interface.getHandle("joint9");
    FAIL() << "expected UnknownHandleError";
  } catch (const servoloop::UnknownHandleError& e) {
    EXPECT_CONTAINS(e.what(), "VelocityJointSaturationInterface has no handle for joint 'joint9'");
    EXPECT_CONTAINS(e.what(), "it has: joint1");
  }
  hi::InterfaceManager manager;
  manager.registerInterface(&limits_interface);
  EXPECT_EQ(manager.get<hi::VelocityJointSaturationInterface>(), &limits_interface);
  EXPECT_EQ(manager.getByName("VelocityJointSaturationInterface"), &limits_interface);
}
