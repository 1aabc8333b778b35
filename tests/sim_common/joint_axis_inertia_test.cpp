// The inertia about a joint axis, against hand calculations with the
// parallel-axis theorem.
#include <gtest/gtest.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/sim_common/joint_axis_inertia.hpp"
#include "sim_test_support.hpp"

namespace servoloop::sim_common {
namespace {

TEST(JointAxisInertia, SeedLink2AboutJoint1) {
  const auto model = loadRobotModelFile(sim_testing::seedUrdfPath(true));
  EXPECT_NEAR(jointAxisInertia(*model, "joint1"), sim_testing::kSeedLink2AxisInertia, 1e-12);
}

TEST(JointAxisInertia, ArmWithOffsetCentreOfMass) {
  // iyy 0.01 at the centre of mass, 1 kg at 1.5 m from the axis: 0.01 + 2.25.
  const auto model = parseRobotModel(sim_testing::armUrdf(1.0, sim_testing::kEffortInterface, "continuous", "", 1.5),
                                     "arm.urdf");
  EXPECT_NEAR(jointAxisInertia(*model, "arm_joint"), 2.26, 1e-12);
}

TEST(JointAxisInertia, PrismaticJointMovesTheSubtreeMass) {
  const auto model = parseRobotModel(
      sim_testing::armUrdf(1.0, sim_testing::kEffortInterface, "prismatic",
                           R"(<limit lower="-1" upper="1" effort="10" velocity="1"/>)"),
      "arm.urdf");
  EXPECT_NEAR(jointAxisInertia(*model, "arm_joint"), 1.0, 1e-12);
}

TEST(JointAxisInertia, SubtreeThroughAFixedJointWithARotatedInertialFrame) {
  // The tool is fixed 2 m along x; its inertial frame is turned 90° about z, so
  // its ixx (0.3) lies along the joint's y axis: 1.01 (arm) + 0.3 + 2 kg · (2 m)².
  const std::string urdf = R"(<?xml version="1.0"?>
<robot name="r">
  <link name="world"/>
  <joint name="j" type="continuous">
    <parent link="world"/><child link="arm"/><axis xyz="0 1 0"/>
  </joint>
  <link name="arm">
    <inertial><origin xyz="1 0 0"/><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <joint name="tool_mount" type="fixed">
    <parent link="arm"/><child link="tool"/><origin xyz="2 0 0"/>
  </joint>
  <link name="tool">
    <inertial><origin xyz="0 0 0" rpy="0 0 1.5707963267948966"/><mass value="2"/>
      <inertia ixx="0.3" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.2"/></inertial>
  </link>
</robot>)";
  const auto model = parseRobotModel(urdf, "tool.urdf");
  EXPECT_NEAR(jointAxisInertia(*model, "j"), 1.01 + 0.3 + 8.0, 1e-9);
}

TEST(JointAxisInertia, RefusesFixedAndUnknownJoints) {
  const auto model = loadRobotModelFile(sim_testing::seedUrdfPath(true));
  EXPECT_THROW(jointAxisInertia(*model, "glue_robot_to_world"), ConfigError);
  EXPECT_THROW(jointAxisInertia(*model, "nope"), ConfigError);
}

}  // namespace
}  // namespace servoloop::sim_common
