// The mujoco backend through SimRobotHW: the seed robots, a 50:1 geared motor
// lifting a horizontal arm against gravity, rotor inertia from the YAML, and
// the motors bounded by the motor limit, against hand calculations and RK4
// references (τ = I·q̈ with the URDF inertia about the axis).
#include <cmath>

#include <gtest/gtest.h>

#include "mujoco_robot_hw.hpp"
#include "rk4_reference.hpp"
#include "servoloop/hardware_interface/actuator_interfaces.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/sim_mujoco/mujoco_physics.hpp"
#include "sim_test_support.hpp"

namespace servoloop::sim_mujoco {
namespace {

namespace hi = hardware_interface;
using sim_testing::armUrdf;
using sim_testing::controllerClaiming;
using sim_testing::makeInfo;

constexpr double kDt = 0.001;
constexpr Duration kPeriod(kDt);
constexpr double kG = 9.81;
// The test arm: 1 kg at 1 m, iyy 0.01: 1.01 kg·m² about the axis.
constexpr double kArmInertia = 1.01;

void cycle(MujocoRobotHW& hw, hi::JointHandle& handle, double command) {
  hw.read(Time(), kPeriod);
  handle.setCommand(command);
  hw.write(Time(), kPeriod);
  hw.step();
  hw.read(Time(), kPeriod);
}

TEST(MujocoRobotHW, SeedRobot2OffersJoint1ThroughMotor1AndSaturatesEffortBeforeTheEngine) {
  MujocoRobotHW hw;
  const std::string path = sim_testing::seedUrdfPath(true);
  hw.init(makeInfo(sim_testing::readFile(path), "", path));
  EXPECT_STREQ(hw.engine().name(), "mujoco");
  EXPECT_EQ(hw.get<hi::EffortJointInterface>()->getNames(), std::vector<std::string>{"joint1"});
  EXPECT_EQ(hw.get<hi::ActuatorStateInterface>()->getNames(), std::vector<std::string>{"motor1"});
  hw.doSwitch({controllerClaiming("joint1_position_controller", "EffortJointInterface", {"joint1"})}, {});
  hi::JointHandle handle = hw.get<hi::EffortJointInterface>()->getHandle("joint1");

  // 50 N·m asked, 10 N·m applied, from rest upright: I q̇' = τ − b q̇ gives
  // q̇(dt) = τ/b (1 − exp(−b dt / I)); the gravity torque m g d q that builds up
  // as the link leaves the top adds (m g d / I)(τ / I) dt³ / 6.
  cycle(hw, handle, 50.0);
  EXPECT_DOUBLE_EQ(hw.appliedCommand(JointIndex(0)).value, 10.0);
  EXPECT_DOUBLE_EQ(handle.getEffort(), 10.0);
  const double inertia = sim_testing::kSeedLink2AxisInertia;
  const double expected = 10.0 / 1.0 * (1.0 - std::exp(-1.0 * kDt / inertia)) +
                          (1.0 * kG * 0.5 / inertia) * (10.0 / inertia) * kDt * kDt * kDt / 6.0;
  EXPECT_NEAR(handle.getVelocity(), expected, 1e-6 * expected);
}

// The horizontal arm feels +9.81 N·m of gravity about +y (q̈ = g cos q / I
// with q = 0 horizontal). Through a 50:1 gear a 0.2 N·m motor gives −10 N·m:
// the arm rises (q < 0).
struct LiftResult {
  double joint_position;
  double joint_velocity;
  double joint_effort;
  double motor_velocity;
  double motor_effort;
};

LiftResult lift(double reduction, double motor_max_effort, int steps, double rotor_inertia = 0.0) {
  MujocoRobotHW hw;
  hw.init(makeInfo(armUrdf(reduction, sim_testing::kEffortInterface),
                   "actuators: {arm_motor: {max_effort: " + std::to_string(motor_max_effort) +
                       ", rotor_inertia: " + std::to_string(rotor_inertia) + "}}"));
  hw.doSwitch({controllerClaiming("e", "EffortJointInterface", {"arm_joint"})}, {});
  hi::JointHandle joint = hw.get<hi::EffortJointInterface>()->getHandle("arm_joint");
  const hi::ActuatorStateHandle motor = hw.get<hi::ActuatorStateInterface>()->getHandle("arm_motor");
  for (int k = 0; k < steps; ++k) cycle(hw, joint, -1000.0);
  return {joint.getPosition(), joint.getVelocity(), joint.getEffort(), motor.getVelocity(), motor.getEffort()};
}

// The arm under a constant joint effort τ and gravity, with `inertia` about the axis.
sim_testing::JointTrajectorySample armReference(double effort, double inertia, int steps) {
  return sim_testing::integrateRk4([&](double q, double) { return (effort + kG * std::cos(q)) / inertia; }, 0.0,
                                   0.0, steps * kDt, kDt)
      .back();
}

TEST(MujocoRobotHW, FiftyToOneGearLetsASmallMotorLiftTheArm) {
  const int n = 300;
  const LiftResult geared = lift(50.0, 0.2, n);
  const auto reference = armReference(-10.0, kArmInertia, n);
  EXPECT_NEAR(geared.joint_position, reference.position[0], 1e-9);
  EXPECT_NEAR(geared.joint_velocity, reference.velocity[0], 1e-9);
  EXPECT_LT(geared.joint_position, 0.0) << "the arm must rise";
  EXPECT_NEAR(geared.joint_effort, -10.0, 1e-9);
  EXPECT_NEAR(geared.motor_effort, -0.2, 1e-12);
  EXPECT_NEAR(geared.motor_velocity, 50.0 * geared.joint_velocity, 1e-9);

  // 0.19 N·m through the same gear is 9.5 N·m < 9.81: the arm sinks.
  EXPECT_GT(lift(50.0, 0.19, n).joint_position, 0.0);
  // The same 0.2 N·m motor without the gear: the arm falls almost freely.
  const LiftResult direct = lift(1.0, 0.2, n);
  EXPECT_NEAR(direct.joint_velocity, armReference(-0.2, kArmInertia, n).velocity[0], 1e-9);
  EXPECT_NEAR(direct.joint_effort, -0.2, 1e-12);
}

TEST(MujocoRobotHW, RotorInertiaBehindTheGearSlowsTheArmBySquaredReduction) {
  // 1e-4 kg·m² rotor behind 50:1: the joint feels 50²·1e-4 = 0.25 kg·m² more.
  const int n = 300;
  const LiftResult geared = lift(50.0, 0.2, n, 1e-4);
  const auto reference = armReference(-10.0, kArmInertia + 0.25, n);
  EXPECT_NEAR(geared.joint_position, reference.position[0], 1e-9);
  EXPECT_NEAR(geared.joint_velocity, reference.velocity[0], 1e-9);
  EXPECT_GT(std::abs(geared.joint_velocity - armReference(-10.0, kArmInertia, n).velocity[0]), 1e-3)
      << "the rotor inertia must show";
}

TEST(MujocoRobotHW, VelocityAndPositionCommandsGoThroughTheMotors) {
  MujocoRobotHW hw;
  hw.init(makeInfo(armUrdf(1.0, sim_testing::kAllJointInterfaces), "sim: {gravity: [0, 0, 0]}"));
  hw.doSwitch({controllerClaiming("v", "VelocityJointInterface", {"arm_joint"})}, {});
  hi::JointHandle velocity = hw.get<hi::VelocityJointInterface>()->getHandle("arm_joint");
  for (int k = 0; k < 500; ++k) cycle(hw, velocity, 0.5);
  EXPECT_NEAR(velocity.getVelocity(), 0.5, 1e-9);

  const auto position_controller = controllerClaiming("p", "PositionJointInterface", {"arm_joint"});
  hw.doSwitch({position_controller}, {controllerClaiming("v", "VelocityJointInterface", {"arm_joint"})});
  hi::JointHandle position = hw.get<hi::PositionJointInterface>()->getHandle("arm_joint");
  for (int k = 0; k < 1000; ++k) cycle(hw, position, -0.3);
  EXPECT_NEAR(position.getPosition(), -0.3, 1e-6);
}

TEST(MujocoRobotHW, PositionMotorIsBoundedByTheMotorLimitThroughTheGear) {
  // Holding the horizontal arm needs 9.81 N·m. A 0.2 N·m motor behind 50:1
  // gives 10 N·m: it holds. A 0.19 N·m one gives 9.5 N·m: the arm sags.
  const auto hold = [](double motor_max_effort) {
    MujocoRobotHW hw;
    hw.init(makeInfo(armUrdf(50.0, sim_testing::kAllJointInterfaces),
                     "actuators: {arm_motor: {max_effort: " + std::to_string(motor_max_effort) + "}}"));
    hw.doSwitch({controllerClaiming("p", "PositionJointInterface", {"arm_joint"})}, {});
    hi::JointHandle position = hw.get<hi::PositionJointInterface>()->getHandle("arm_joint");
    double max_effort = 0.0;
    for (int k = 0; k < 1000; ++k) {
      cycle(hw, position, 0.0);
      max_effort = std::max(max_effort, std::abs(position.getEffort()));
    }
    EXPECT_LE(max_effort, 50.0 * motor_max_effort + 1e-9);
    return position.getPosition();
  };
  EXPECT_NEAR(hold(0.2), 0.0, 1e-3);
  // Sagging under (9.81 − 9.5) N·m: q ≈ ½ · 0.31 / 1.01 · t² = 0.15 rad at 1 s.
  const double sag = hold(0.19);
  EXPECT_GT(sag, 0.1);
  EXPECT_LT(sag, 0.16);
}

TEST(MujocoRobotHW, EmergencyStopHoldsAPositionControlledArmAgainstGravity) {
  MujocoRobotHW hw;
  hw.init(makeInfo(armUrdf(1.0, sim_testing::kAllJointInterfaces)));
  hw.doSwitch({controllerClaiming("p", "PositionJointInterface", {"arm_joint"})}, {});
  hi::JointHandle position = hw.get<hi::PositionJointInterface>()->getHandle("arm_joint");
  for (int k = 0; k < 1000; ++k) cycle(hw, position, -0.3);
  const double engaged_at = position.getPosition();
  hw.setEmergencyStop(true);
  for (int k = 0; k < 500; ++k) cycle(hw, position, 1.0);
  EXPECT_NEAR(position.getPosition(), engaged_at, 1e-6);
  EXPECT_DOUBLE_EQ(hw.appliedCommand(JointIndex(0)).value, engaged_at);
}

TEST(MujocoRobotHW, InitialPositionsAndResetFromTheYaml) {
  MujocoRobotHW hw;
  const std::string path = sim_testing::seedUrdfPath(true);
  hw.init(makeInfo(sim_testing::readFile(path), "sim: {initial_positions: {joint1: 0.5}}", path));
  hi::JointHandle handle = hw.get<hi::EffortJointInterface>()->getHandle("joint1");
  hw.read(Time(), kPeriod);
  EXPECT_DOUBLE_EQ(handle.getPosition(), 0.5);
  for (int k = 0; k < 100; ++k) cycle(hw, handle, 0.0);
  EXPECT_GT(handle.getPosition(), 0.5) << "mode none: zero effort, gravity pulls the link down";
  hw.reset();
  hw.read(Time(), kPeriod);
  EXPECT_DOUBLE_EQ(handle.getPosition(), 0.5);
  EXPECT_EQ(handle.getVelocity(), 0.0);
  EXPECT_EQ(hw.simTime().seconds, 0.0);
}

}  // namespace
}  // namespace servoloop::sim_mujoco
