// The bullet backend: the seed robots, limits before the engine, and a 50:1
// geared motor lifting a horizontal arm against gravity, against hand
// calculations (τ = I·q̈ with the URDF inertia about the axis).
#include <cmath>

#include <gtest/gtest.h>

#include "bullet_robot_hw.hpp"
#include "servoloop/hardware_interface/actuator_interfaces.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "sim_test_support.hpp"

namespace servoloop::sim_bullet {
namespace {

namespace hi = hardware_interface;
using sim_common::JointCommandMode;
using sim_testing::armUrdf;
using sim_testing::controllerClaiming;
using sim_testing::makeInfo;

constexpr double kDt = 0.001;
constexpr Duration kPeriod(kDt);

void cycle(BulletRobotHW& hw, hi::JointHandle& handle, double command) {
  hw.read(Time(), kPeriod);
  handle.setCommand(command);
  hw.write(Time(), kPeriod);
  hw.step();
  hw.read(Time(), kPeriod);
}

TEST(BulletRobotHW, SeedRobot2OffersJoint1ThroughMotor1AndSaturatesEffortBeforeTheEngine) {
  BulletRobotHW hw;
  const std::string path = sim_testing::seedUrdfPath(true);
  hw.init(makeInfo(sim_testing::readFile(path), "", path));
  EXPECT_EQ(hw.get<hi::EffortJointInterface>()->getNames(), std::vector<std::string>{"joint1"});
  EXPECT_EQ(hw.get<hi::ActuatorStateInterface>()->getNames(), std::vector<std::string>{"motor1"});
  hw.doSwitch({controllerClaiming("joint1_position_controller", "EffortJointInterface", {"joint1"})}, {});
  hi::JointHandle handle = hw.get<hi::EffortJointInterface>()->getHandle("joint1");

  // 50 N·m asked, 10 N·m applied; upright link (no gravity torque at q = 0),
  // at rest (no damping torque): one step gives q̇ = 10 / 0.35 · dt.
  cycle(hw, handle, 50.0);
  EXPECT_DOUBLE_EQ(hw.appliedCommand(JointIndex(0)).value, 10.0);
  EXPECT_DOUBLE_EQ(handle.getEffort(), 10.0);
  EXPECT_NEAR(handle.getVelocity(), 10.0 / sim_testing::kSeedLink2AxisInertia * kDt, 1e-3 * 0.0286);
}

TEST(BulletRobotHW, SeedRobot1ImplicitTransmissionWithoutGravity) {
  BulletRobotHW hw;
  const std::string path = sim_testing::seedUrdfPath(false);
  hw.init(makeInfo(sim_testing::readFile(path), "sim: {gravity: [0, 0, 0]}", path));
  EXPECT_EQ(hw.transmissions().implicitTransmissionJoints(), std::vector<std::string>{"joint1"});
  hw.doSwitch({controllerClaiming("e", "EffortJointInterface", {"joint1"})}, {});
  hi::JointHandle handle = hw.get<hi::EffortJointInterface>()->getHandle("joint1");
  const int n = 200;
  for (int k = 0; k < n; ++k) cycle(hw, handle, 2.0);
  EXPECT_NEAR(handle.getVelocity(), n * kDt * 2.0 / sim_testing::kSeedLink2AxisInertia, 2e-3 * 1.14);
}

// The horizontal arm (1 kg at 1 m, 1.01 kg·m² about the axis) feels +9.81 N·m
// of gravity about +y. Through a 50:1 gear a 0.2 N·m motor gives -10 N·m:
// the arm rises (q < 0) with q̈ = (−10 + 9.81) / 1.01.
struct LiftResult {
  double joint_position;
  double joint_velocity;
  double joint_effort;
  double motor_velocity;
  double motor_effort;
};

LiftResult lift(double reduction, double motor_max_effort, int steps) {
  BulletRobotHW hw;
  hw.init(makeInfo(armUrdf(reduction, sim_testing::kEffortInterface),
                   "actuators: {arm_motor: {max_effort: " + std::to_string(motor_max_effort) + "}}"));
  hw.doSwitch({controllerClaiming("e", "EffortJointInterface", {"arm_joint"})}, {});
  hi::JointHandle joint = hw.get<hi::EffortJointInterface>()->getHandle("arm_joint");
  const hi::ActuatorStateHandle motor = hw.get<hi::ActuatorStateInterface>()->getHandle("arm_motor");
  for (int k = 0; k < steps; ++k) cycle(hw, joint, -1000.0);
  return {joint.getPosition(), joint.getVelocity(), joint.getEffort(), motor.getVelocity(), motor.getEffort()};
}

TEST(BulletRobotHW, FiftyToOneGearLetsASmallMotorLiftTheArm) {
  const int n = 300;
  const LiftResult geared = lift(50.0, 0.2, n);
  const double acceleration = (-10.0 + 9.81) / 1.01;
  // Semi-implicit Euler from rest: q_n = a·dt²·n(n+1)/2 (the gravity torque's
  // cos q stays within 1e-4 of 1 over this range).
  EXPECT_NEAR(geared.joint_position, acceleration * kDt * kDt * n * (n + 1) / 2.0, 0.02 * 0.0085);
  EXPECT_NEAR(geared.joint_velocity, acceleration * n * kDt, 0.02 * 0.056);
  EXPECT_LT(geared.joint_position, 0.0) << "the arm must rise";
  EXPECT_NEAR(geared.joint_effort, -10.0, 1e-9);
  EXPECT_NEAR(geared.motor_effort, -0.2, 1e-12);
  EXPECT_NEAR(geared.motor_velocity, 50.0 * geared.joint_velocity, 1e-9);

  // 0.19 N·m through the same gear is 9.5 N·m < 9.81: the arm sinks.
  EXPECT_GT(lift(50.0, 0.19, n).joint_position, 0.0);
  // The same 0.2 N·m motor without the gear: the arm falls almost freely.
  const LiftResult direct = lift(1.0, 0.2, n);
  EXPECT_NEAR(direct.joint_velocity, (9.81 - 0.2) / 1.01 * n * kDt, 0.03 * 2.85);
  EXPECT_NEAR(direct.joint_effort, -0.2, 1e-12);
}

TEST(BulletRobotHW, VelocityAndPositionCommandsGoThroughTheMotors) {
  BulletRobotHW hw;
  hw.init(makeInfo(armUrdf(1.0, sim_testing::kAllJointInterfaces), "sim: {gravity: [0, 0, 0]}"));
  hw.doSwitch({controllerClaiming("v", "VelocityJointInterface", {"arm_joint"})}, {});
  hi::JointHandle velocity = hw.get<hi::VelocityJointInterface>()->getHandle("arm_joint");
  for (int k = 0; k < 500; ++k) cycle(hw, velocity, 0.5);
  EXPECT_NEAR(velocity.getVelocity(), 0.5, 1e-3);

  const auto position_controller = controllerClaiming("p", "PositionJointInterface", {"arm_joint"});
  hw.doSwitch({position_controller}, {controllerClaiming("v", "VelocityJointInterface", {"arm_joint"})});
  hi::JointHandle position = hw.get<hi::PositionJointInterface>()->getHandle("arm_joint");
  for (int k = 0; k < 1000; ++k) cycle(hw, position, -0.3);
  EXPECT_NEAR(position.getPosition(), -0.3, 1e-3);
}

TEST(BulletRobotHW, EmergencyStopHoldsAPositionControlledArmAgainstGravity) {
  BulletRobotHW hw;
  hw.init(makeInfo(armUrdf(1.0, sim_testing::kAllJointInterfaces)));
  hw.doSwitch({controllerClaiming("p", "PositionJointInterface", {"arm_joint"})}, {});
  hi::JointHandle position = hw.get<hi::PositionJointInterface>()->getHandle("arm_joint");
  for (int k = 0; k < 1000; ++k) cycle(hw, position, -0.3);
  const double engaged_at = position.getPosition();
  hw.setEmergencyStop(true);
  for (int k = 0; k < 500; ++k) cycle(hw, position, 1.0);
  EXPECT_NEAR(position.getPosition(), engaged_at, 1e-3);
  EXPECT_DOUBLE_EQ(hw.appliedCommand(JointIndex(0)).value, engaged_at);
}

}  // namespace
}  // namespace servoloop::sim_bullet
