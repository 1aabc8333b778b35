// The real-time propagation of RobotTransmissions allocates nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "alloc_counter.hpp"
#include "servoloop/transmissions/robot_transmissions.hpp"

namespace st = servoloop::transmissions;
using servoloop::ActuatorIndex;
using servoloop::JointIndex;

namespace {
// One transmission of each type, every command interface in use.
const char* kRobot = R"(<?xml version="1.0"?>
<robot name="all_kinds">
  <link name="l0"/><link name="l1"/><link name="l2"/><link name="l3"/><link name="l4"/><link name="l5"/>
  <joint name="s" type="continuous"><parent link="l0"/><child link="l1"/></joint>
  <joint name="d1" type="continuous"><parent link="l1"/><child link="l2"/></joint>
  <joint name="d2" type="continuous"><parent link="l2"/><child link="l3"/></joint>
  <joint name="f1" type="continuous"><parent link="l3"/><child link="l4"/></joint>
  <joint name="f2" type="continuous"><parent link="l4"/><child link="l5"/></joint>
  <transmission name="simple"><type>transmission_interface/SimpleTransmission</type>
    <joint name="s"><hardwareInterface>EffortJointInterface</hardwareInterface>
      <hardwareInterface>VelocityJointInterface</hardwareInterface>
      <hardwareInterface>PositionJointInterface</hardwareInterface></joint>
    <actuator name="sm"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
  <transmission name="diff"><type>transmission_interface/DifferentialTransmission</type>
    <joint name="d1"><role>joint1</role><hardwareInterface>EffortJointInterface</hardwareInterface>
      <hardwareInterface>PositionJointInterface</hardwareInterface></joint>
    <joint name="d2"><role>joint2</role><hardwareInterface>EffortJointInterface</hardwareInterface>
      <hardwareInterface>PositionJointInterface</hardwareInterface></joint>
    <actuator name="dm1"><role>actuator1</role><mechanicalReduction>10</mechanicalReduction></actuator>
    <actuator name="dm2"><role>actuator2</role><mechanicalReduction>-20</mechanicalReduction></actuator>
  </transmission>
  <transmission name="fourbar"><type>transmission_interface/FourBarLinkageTransmission</type>
    <joint name="f1"><role>joint1</role><hardwareInterface>VelocityJointInterface</hardwareInterface></joint>
    <joint name="f2"><role>joint2</role><hardwareInterface>VelocityJointInterface</hardwareInterface></joint>
    <actuator name="fm1"><role>actuator1</role><mechanicalReduction>3</mechanicalReduction></actuator>
    <actuator name="fm2"><role>actuator2</role><mechanicalReduction>7</mechanicalReduction></actuator>
  </transmission>
</robot>)";
}  // namespace

// Guards against a counter that is not linked in (the real test would then
// pass without measuring anything).
TEST(RobotTransmissionsAllocation, CounterSeesAnAllocation) {
  // Stored through a volatile pointer so the compiler cannot elide the new.
  static double* volatile escaped = nullptr;
  servoloop::testing::AllocationCounter counter;
  escaped = new double(1.0);
  delete escaped;
  EXPECT_GE(counter.allocations(), 1u);
}

TEST(RobotTransmissionsAllocation, HundredThousandPropagationsAllocateNothing) {
  auto rt = st::RobotTransmissions::fromUrdf(kRobot, {false, "all_kinds.urdf"});
  ASSERT_EQ(rt->numJoints(), 5u);
  ASSERT_EQ(rt->numActuators(), 5u);

  double sink = 0.0;
  servoloop::testing::AllocationCounter counter;
  for (int cycle = 0; cycle < 100000; ++cycle) {
    const double value = 1e-3 * cycle;
    for (std::size_t a = 0; a < rt->numActuators(); ++a) {
      rt->actuator(ActuatorIndex(a)).position = value + static_cast<double>(a);
    }
    rt->actuatorStateToJointState();
    for (std::size_t j = 0; j < rt->numJoints(); ++j) {
      st::JointValues& joint = rt->joint(JointIndex(j));
      joint.effort_command = joint.velocity_command = joint.position_command = joint.position;
    }
    rt->jointCommandToActuatorCommand();
    rt->jointStateToActuatorState();
    rt->actuatorEffortToJointEffort();
    rt->actuatorVelocityToJointVelocity();
    rt->actuatorPositionToJointPosition();
    rt->actuatorCommandToJointCommand();
    sink += rt->joint(JointIndex(cycle % 5)).position_command;
  }
  EXPECT_EQ(counter.allocations(), 0u);
  EXPECT_TRUE(std::isfinite(sink));
}
