// The mock backend's ideal actuators, checked against hand calculations
// (semi-implicit Euler with the URDF inertia about the joint axis): what only
// they do, targets met in one step and no gravity. What every backend does
// alike is in tests/sim_common/robot_hw_conformance_test.cpp.
#include <cmath>

#include <gtest/gtest.h>

#include "mock_robot_hw.hpp"
#include "servoloop/hardware_interface/actuator_interfaces.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "sim_test_support.hpp"

namespace servoloop::sim_mock {
namespace {

namespace hi = hardware_interface;
using sim_testing::armUrdf;
using sim_testing::controllerClaiming;
using sim_testing::cycle;
using sim_testing::makeInfo;

constexpr double kDt = sim_testing::kCycleDt;

TEST(MockRobotHW, PositionCommandIsReachedInOneStep) {
  MockRobotHW hw;
  hw.init(makeInfo(armUrdf(1.0, sim_testing::kAllJointInterfaces)));
  hw.doSwitch({controllerClaiming("p", "PositionJointInterface", {"arm_joint"})}, {});
  hi::JointHandle handle = hw.get<hi::PositionJointInterface>()->getHandle("arm_joint");
  cycle(hw, handle, 0.7);
  EXPECT_DOUBLE_EQ(handle.getPosition(), 0.7);
  EXPECT_NEAR(handle.getVelocity(), 0.7 / kDt, 1e-9);  // 0 → 0.7 rad in one step
  cycle(hw, handle, 0.7);
  EXPECT_DOUBLE_EQ(handle.getPosition(), 0.7);
  EXPECT_DOUBLE_EQ(handle.getVelocity(), 0.0);
}

TEST(MockRobotHW, VelocityCommandIsIntegrated) {
  MockRobotHW hw;
  hw.init(makeInfo(armUrdf(1.0, sim_testing::kAllJointInterfaces), "sim: {initial_positions: {arm_joint: 0.1}}"));
  hw.doSwitch({controllerClaiming("v", "VelocityJointInterface", {"arm_joint"})}, {});
  hi::JointHandle handle = hw.get<hi::VelocityJointInterface>()->getHandle("arm_joint");
  EXPECT_DOUBLE_EQ(handle.getPosition(), 0.1);
  for (int k = 0; k < 200; ++k) cycle(hw, handle, 0.5);
  EXPECT_NEAR(handle.getPosition(), 0.1 + 0.5 * 200 * kDt, 1e-12);
  EXPECT_DOUBLE_EQ(handle.getVelocity(), 0.5);
}

TEST(MockRobotHW, EffortAcceleratesTheSeedLinkByTorqueOverItsAxisInertia) {
  // Seed robot 1 (implicit transmission, no limits): I = 0.35 kg·m² about joint1.
  MockRobotHW hw;
  const std::string path = sim_testing::seedUrdfPath(false);
  hw.init(makeInfo(sim_testing::readFile(path), "", path));
  hw.doSwitch({controllerClaiming("e", "EffortJointInterface", {"joint1"})}, {});
  hi::JointHandle handle = hw.get<hi::EffortJointInterface>()->getHandle("joint1");
  const double acceleration = 2.0 / sim_testing::kSeedLink2AxisInertia;
  const int n = 500;
  for (int k = 0; k < n; ++k) cycle(hw, handle, 2.0);
  // Semi-implicit Euler: v_n = n·a·dt, q_n = a·dt²·n(n+1)/2.
  EXPECT_NEAR(handle.getVelocity(), n * acceleration * kDt, 1e-9);
  EXPECT_NEAR(handle.getPosition(), acceleration * kDt * kDt * n * (n + 1) / 2.0, 1e-9);
  EXPECT_DOUBLE_EQ(handle.getEffort(), 2.0);
  EXPECT_NEAR(hw.simTime().seconds, n * kDt, 1e-12);
}

TEST(MockRobotHW, AStoppedControllerLeavesTheJointCoasting) {
  // Seed robot 2: one step of its 10 N·m limit sets the link moving (the
  // conformance suite checks that step), then the controller stops.
  MockRobotHW hw;
  const std::string path = sim_testing::seedUrdfPath(true);
  hw.init(makeInfo(sim_testing::readFile(path), "", path));
  const auto controller = controllerClaiming("joint1_position_controller", "EffortJointInterface", {"joint1"});
  hw.doSwitch({controller}, {});
  hi::JointHandle handle = hw.get<hi::EffortJointInterface>()->getHandle("joint1");
  cycle(hw, handle, 50.0);
  ASSERT_GT(handle.getVelocity(), 0.0);

  hw.doSwitch({}, {controller});
  const double velocity = handle.getVelocity();
  cycle(hw, handle, 50.0);
  EXPECT_DOUBLE_EQ(handle.getEffort(), 0.0);  // stopped: zero effort, coasts
  EXPECT_DOUBLE_EQ(handle.getVelocity(), velocity);
}

TEST(MockRobotHW, FiftyToOneGearedMotorWithRotorInertia) {
  // Motor: 0.2 N·m, rotor 1e-4 kg·m²; gear 50:1. At the joint: at most 10 N·m,
  // inertia 0.01 + 1² (arm) + 50²·1e-4 (rotor) = 1.26 kg·m².
  MockRobotHW hw;
  hw.init(makeInfo(armUrdf(50.0, sim_testing::kEffortInterface),
                   "actuators: {arm_motor: {max_effort: 0.2, rotor_inertia: 1.0e-4}}"));
  hw.doSwitch({controllerClaiming("e", "EffortJointInterface", {"arm_joint"})}, {});
  hi::JointHandle joint = hw.get<hi::EffortJointInterface>()->getHandle("arm_joint");
  const hi::ActuatorStateHandle motor = hw.get<hi::ActuatorStateInterface>()->getHandle("arm_motor");
  const double acceleration = 10.0 / 1.26;
  const int n = 300;
  for (int k = 0; k < n; ++k) cycle(hw, joint, 100.0);
  EXPECT_NEAR(joint.getVelocity(), n * acceleration * kDt, 1e-9);
  EXPECT_NEAR(joint.getEffort(), 10.0, 1e-12);
  EXPECT_NEAR(motor.getVelocity(), 50.0 * joint.getVelocity(), 1e-9);
  EXPECT_NEAR(motor.getPosition(), 50.0 * joint.getPosition(), 1e-9);
  EXPECT_NEAR(motor.getEffort(), 0.2, 1e-12);
  EXPECT_NEAR(joint.getEffort(), 50.0 * motor.getEffort(), 1e-12);
}

TEST(MockRobotHW, EmergencyStopHoldsPositionJoints) {
  MockRobotHW hw;
  hw.init(makeInfo(armUrdf(1.0, sim_testing::kAllJointInterfaces)));
  hw.doSwitch({controllerClaiming("p", "PositionJointInterface", {"arm_joint"})}, {});
  hi::JointHandle handle = hw.get<hi::PositionJointInterface>()->getHandle("arm_joint");
  cycle(hw, handle, 0.4);
  hw.setEmergencyStop(true);
  for (int k = 0; k < 10; ++k) cycle(hw, handle, 1.0);
  EXPECT_DOUBLE_EQ(handle.getPosition(), 0.4);
  hw.setEmergencyStop(false);
  cycle(hw, handle, 1.0);
  EXPECT_DOUBLE_EQ(handle.getPosition(), 1.0);
}

}  // namespace
}  // namespace servoloop::sim_mock
