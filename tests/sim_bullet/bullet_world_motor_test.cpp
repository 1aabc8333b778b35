// BulletWorld's joint motors and effort readout on the seed robot
// (minimal_robot_description_w_jnt_ctl.urdf: link2 I = 0.35 kg m² about
// joint1, damping b = 1, <limit effort> 10 N m, stops at [0, 2] rad), against
// hand-written one-step recursions and static balances.
//
// Bullet applies the damping torque -b·v_k from the start-of-step velocity and
// then solves the motor for the end-of-step velocity, so a motor saturated at
// u gives exactly v_{k+1} = v_k + dt·(u − b·v_k)/I; an unsaturated velocity
// motor reaches its target in one step.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "servoloop/description/robot_model.hpp"
#include "servoloop/sim_bullet/bullet_world.hpp"

namespace servoloop::sim_bullet {
namespace {

constexpr double kG = 9.81;
constexpr double kSeedInertia = 0.35;  // kg m², link2 about joint1
constexpr double kSeedDamping = 1.0;   // N m s/rad
constexpr double kSeedGravityTorque = 1.0 * kG * 0.5;  // m g d, N m (times sin q; q = 0 upright)

std::shared_ptr<const urdf::ModelInterface> seedWithControl() {
  return loadRobotModelFile(std::string(SERVOLOOP_SEED_DIR) + "/minimal_robot_description_w_jnt_ctl.urdf");
}

WorldSettings noGravity() {
  WorldSettings s;
  s.gravity = Eigen::Vector3d::Zero();
  return s;
}

// Runs a velocity motor (target `target`, bound `bound`) from rest at 0.5 rad
// for `steps` steps and checks every step against the saturated recursion.
void expectSaturatedVelocityMotor(double bound, double target, int steps) {
  BulletWorld world(*seedWithControl(), noGravity());
  EXPECT_DOUBLE_EQ(world.jointMotorEffortLimit(0), 10.0) << "default: the URDF <limit effort>";
  world.setJointMotorEffortLimit(0, bound);
  EXPECT_DOUBLE_EQ(world.jointMotorEffortLimit(0), bound);
  world.setJointState(0, 0.5, 0.0);
  const double dt = world.timeStep();
  double v = 0.0;
  for (int k = 0; k < steps; ++k) {
    world.setJointVelocityTarget(0, target);
    world.step();
    v += dt * (bound - kSeedDamping * v) / kSeedInertia;
    ASSERT_NEAR(world.jointVelocity(0), v, 1e-9) << "bound " << bound << ", step " << k;
    ASSERT_NEAR(world.jointAppliedEffort(0), bound, 1e-9 * bound) << "bound " << bound << ", step " << k;
  }
  ASSERT_LT(v, target) << "the case must keep the motor saturated";
}

TEST(BulletWorldMotor, VelocityMotorIsBoundedByTheMotorEffortLimitTighterThanTheUrdf) {
  // 2 N m against damping: the velocity tends to 2 rad/s, never the 5 asked.
  expectSaturatedVelocityMotor(2.0, 5.0, 200);
}

TEST(BulletWorldMotor, VelocityMotorIsBoundedByTheMotorEffortLimitLooserThanTheUrdf) {
  // A YAML joint limit may be looser than the URDF's 10 N m: 30 N m it is.
  expectSaturatedVelocityMotor(30.0, 5.0, 40);
}

TEST(BulletWorldMotor, NewBoundAppliesToARunningPositionMotor) {
  BulletWorld world(*seedWithControl(), noGravity());
  world.setJointState(0, 0.5, 0.0);
  world.setJointPositionTarget(0, 1.5);
  world.step();
  // (1.5 − 0.5)/20 ms = 50 rad/s wanted: needs far more than 10 N m; saturated.
  EXPECT_NEAR(world.jointAppliedEffort(0), 10.0, 1e-9);
  world.setJointMotorEffortLimit(0, 1.5);
  world.step();
  EXPECT_NEAR(world.jointAppliedEffort(0), 1.5, 1e-9);
}

TEST(BulletWorldMotor, PositionMotorReportsTheEffortHoldingTheLinkAgainstGravity) {
  BulletWorld world(*seedWithControl());
  world.setJointState(0, 0.5, 0.0);
  for (int k = 0; k < 1500; ++k) {
    world.setJointPositionTarget(0, 1.2);
    world.step();
  }
  ASSERT_NEAR(world.jointPosition(0), 1.2, 1e-6);
  // At rest at 1.2 rad gravity pushes with +m g d sin q; the motor balances it.
  const double holding = -kSeedGravityTorque * std::sin(1.2);  // −4.57 N m
  EXPECT_NEAR(world.jointAppliedEffort(0), holding, 1e-4 * std::abs(holding));
}

TEST(BulletWorldMotor, VelocityMotorAtItsTargetReportsTheEffortCancellingTheDamping) {
  BulletWorld world(*seedWithControl(), noGravity());
  world.setJointState(0, 0.5, 0.0);
  for (int k = 0; k < 200; ++k) {
    world.setJointVelocityTarget(0, 0.3);
    world.step();
  }
  ASSERT_NEAR(world.jointVelocity(0), 0.3, 1e-12);
  EXPECT_NEAR(world.jointAppliedEffort(0), kSeedDamping * 0.3, 1e-9);
}

TEST(BulletWorldMotor, EffortModeReportsTheCommandAndResetClearsIt) {
  BulletWorld world(*seedWithControl(), noGravity());
  world.setJointState(0, 0.5, 0.0);
  EXPECT_EQ(world.jointAppliedEffort(0), 0.0);
  world.setJointEffort(0, -3.0);
  world.step();
  EXPECT_EQ(world.jointAppliedEffort(0), -3.0);
  world.step();  // an effort acts for one step only
  EXPECT_EQ(world.jointAppliedEffort(0), 0.0);
  world.setJointVelocityTarget(0, 0.2);
  world.step();
  EXPECT_GT(world.jointAppliedEffort(0), 0.0);
  world.reset();
  EXPECT_EQ(world.jointAppliedEffort(0), 0.0);
}

}  // namespace
}  // namespace servoloop::sim_bullet
