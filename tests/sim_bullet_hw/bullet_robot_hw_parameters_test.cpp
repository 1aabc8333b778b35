// The bullet backend honours the same parameters as the mujoco backend:
// one place for effort limits (SimRobotHW, URDF + YAML), motor effort limits
// on velocity/position commands, the motor's effort in the joint state, and
// rotor inertia through the gear. Hand calculations: the arm of armUrdf has
// 1.01 kg·m² about its axis and feels +9.81·cos q N·m of gravity.
#include <cmath>

#include <gtest/gtest.h>

#include "bullet_robot_hw.hpp"
#include "servoloop/hardware_interface/actuator_interfaces.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "sim_test_support.hpp"

namespace servoloop::sim_bullet {
namespace {

namespace hi = hardware_interface;
using sim_testing::armUrdf;
using sim_testing::controllerClaiming;
using sim_testing::makeInfo;

constexpr double kDt = 0.001;
constexpr Duration kPeriod(kDt);
constexpr double kArmInertia = 1.01;  // kg·m² about arm_joint
constexpr double kG = 9.81;

void cycle(BulletRobotHW& hw, hi::JointHandle& handle, double command) {
  hw.read(Time(), kPeriod);
  handle.setCommand(command);
  hw.write(Time(), kPeriod);
  hw.step();
  hw.read(Time(), kPeriod);
}

TEST(BulletRobotHWParameters, AYamlEffortLimitLooserThanTheUrdfIsTheOneApplied) {
  // The seed URDF says 10 N·m; the YAML joint limit says 20. SimRobotHW
  // applies the merged limit (20) and the engine does not clamp again at 10.
  BulletRobotHW hw;
  const std::string path = sim_testing::seedUrdfPath(true);
  hw.init(makeInfo(sim_testing::readFile(path), "joint_limits: {joint1: {has_effort_limits: true, max_effort: 20}}",
                   path));
  hw.doSwitch({controllerClaiming("e", "EffortJointInterface", {"joint1"})}, {});
  hi::JointHandle handle = hw.get<hi::EffortJointInterface>()->getHandle("joint1");
  cycle(hw, handle, 50.0);  // upright link at rest: no gravity or damping torque
  EXPECT_DOUBLE_EQ(hw.appliedCommand(JointIndex(0)).value, 20.0);
  EXPECT_DOUBLE_EQ(handle.getEffort(), 20.0);
  EXPECT_NEAR(handle.getVelocity(), 20.0 / sim_testing::kSeedLink2AxisInertia * kDt, 1e-12);
}

TEST(BulletRobotHWParameters, VelocityCommandsAreBoundedByTheGearedMotor) {
  // 0.1 N·m through 50:1: the velocity motor may use 5 N·m at the joint
  // (the URDF gives no effort limit). No gravity, no damping: from rest
  // v_k = k·dt·5/1.01 until the 3 rad/s target, which takes 0.6 s.
  BulletRobotHW hw;
  hw.init(makeInfo(armUrdf(50.0, sim_testing::kAllJointInterfaces),
                   "{sim: {gravity: [0, 0, 0]}, actuators: {arm_motor: {max_effort: 0.1}}}"));
  hw.doSwitch({controllerClaiming("v", "VelocityJointInterface", {"arm_joint"})}, {});
  hi::JointHandle joint = hw.get<hi::VelocityJointInterface>()->getHandle("arm_joint");
  const hi::ActuatorStateHandle motor = hw.get<hi::ActuatorStateInterface>()->getHandle("arm_motor");
  for (int k = 1; k <= 300; ++k) {
    cycle(hw, joint, 3.0);
    ASSERT_NEAR(joint.getVelocity(), k * kDt * 5.0 / kArmInertia, 1e-9) << "cycle " << k;
  }
  EXPECT_NEAR(joint.getEffort(), 5.0, 1e-9);
  EXPECT_NEAR(motor.getEffort(), 0.1, 1e-11);
}

TEST(BulletRobotHWParameters, PositionCommandsReportTheEffortHoldingTheArm) {
  // What joint_states shows in position mode: the motor's effort, here
  // balancing gravity at rest at −0.3 rad: −9.81·cos(−0.3) N·m.
  BulletRobotHW hw;
  hw.init(makeInfo(armUrdf(1.0, sim_testing::kAllJointInterfaces)));
  hw.doSwitch({controllerClaiming("p", "PositionJointInterface", {"arm_joint"})}, {});
  hi::JointHandle joint = hw.get<hi::PositionJointInterface>()->getHandle("arm_joint");
  const hi::ActuatorStateHandle motor = hw.get<hi::ActuatorStateInterface>()->getHandle("arm_motor");
  for (int k = 0; k < 1500; ++k) cycle(hw, joint, -0.3);
  ASSERT_NEAR(joint.getPosition(), -0.3, 1e-6);
  const double holding = -kG * std::cos(-0.3);
  EXPECT_NEAR(joint.getEffort(), holding, 1e-4 * std::abs(holding));
  EXPECT_NEAR(motor.getEffort(), holding, 1e-4 * std::abs(holding));
}

TEST(BulletRobotHWParameters, PositionCommandsAreBoundedByTheMotorEffortLimit) {
  // 0.19 N·m through 50:1 is 9.5 N·m < the 9.81 N·m gravity needs at the
  // horizontal: the position motor cannot lift the arm and it sinks, with the
  // motor at its bound the whole way.
  BulletRobotHW hw;
  hw.init(makeInfo(armUrdf(50.0, sim_testing::kAllJointInterfaces), "actuators: {arm_motor: {max_effort: 0.19}}"));
  hw.doSwitch({controllerClaiming("p", "PositionJointInterface", {"arm_joint"})}, {});
  hi::JointHandle joint = hw.get<hi::PositionJointInterface>()->getHandle("arm_joint");
  for (int k = 0; k < 300; ++k) {
    cycle(hw, joint, -0.5);
    ASSERT_NEAR(joint.getEffort(), -9.5, 1e-9) << "cycle " << k;
  }
  // Semi-implicit Euler from rest with q̈ = (9.81·cos q − 9.5)/1.01, cos q ≈ 1.
  const double acceleration = (kG - 9.5) / kArmInertia;
  EXPECT_NEAR(joint.getVelocity(), acceleration * 300 * kDt, 1e-3 * acceleration * 300 * kDt);
  EXPECT_GT(joint.getPosition(), 0.0) << "the arm sinks";
}

TEST(BulletRobotHWParameters, RotorInertiaIsReflectedThroughTheGear) {
  // J = 1e-4 kg·m² behind 50:1: the joint feels 50²·1e-4 = 0.25 kg·m² more.
  BulletRobotHW hw;
  hw.init(makeInfo(armUrdf(50.0, sim_testing::kEffortInterface),
                   "{sim: {gravity: [0, 0, 0]}, actuators: {arm_motor: {rotor_inertia: 1.0e-4}}}"));
  hw.doSwitch({controllerClaiming("e", "EffortJointInterface", {"arm_joint"})}, {});
  hi::JointHandle joint = hw.get<hi::EffortJointInterface>()->getHandle("arm_joint");
  cycle(hw, joint, 2.0);
  EXPECT_NEAR(joint.getVelocity(), 2.0 * kDt / (kArmInertia + 0.25), 1e-12);
}

}  // namespace
}  // namespace servoloop::sim_bullet
