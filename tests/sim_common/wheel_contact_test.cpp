// Which URDF cylinders count as wheels (and get a tyre's contact profile):
// on a link turned by a revolute or continuous joint about the cylinder's own
// axis, no wider than its radius.
#include <numbers>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "servoloop/sim_common/wheel_contact.hpp"

namespace servoloop::sim_common {
namespace {

urdf::Joint joint(decltype(urdf::Joint::type) type, double x, double y, double z) {
  urdf::Joint j;
  j.type = type;
  j.axis = urdf::Vector3(x, y, z);
  return j;
}

// The usual ROS wheel: the joint axis is the link's z, the cylinder's too.
TEST(WheelContact, ACylinderTurningAboutItsAxisIsAWheel) {
  const urdf::Joint continuous = joint(urdf::Joint::CONTINUOUS, 0, 0, 1);
  EXPECT_TRUE(isWheelCylinder(&continuous, Eigen::Matrix3d::Identity(), 0.1, 0.04));
  const urdf::Joint revolute = joint(urdf::Joint::REVOLUTE, 0, 0, -1);  // either sense
  EXPECT_TRUE(isWheelCylinder(&revolute, Eigen::Matrix3d::Identity(), 0.1, 0.1));
}

// Axis along y in the link frame, the cylinder turned onto it by its origin.
TEST(WheelContact, TheCollisionsOriginMayTurnTheCylinderOntoTheAxis) {
  const urdf::Joint j = joint(urdf::Joint::CONTINUOUS, 0, 1, 0);
  const Eigen::Matrix3d turned = Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  EXPECT_TRUE(isWheelCylinder(&j, turned, 0.1, 0.04));
  EXPECT_FALSE(isWheelCylinder(&j, Eigen::Matrix3d::Identity(), 0.1, 0.04));  // axis across the joint's
}

TEST(WheelContact, OtherCylindersAreNot) {
  const urdf::Joint j = joint(urdf::Joint::CONTINUOUS, 0, 0, 1);
  EXPECT_FALSE(isWheelCylinder(&j, Eigen::Matrix3d::Identity(), 0.1, 0.3));  // a roller, wider than its radius
  EXPECT_FALSE(isWheelCylinder(nullptr, Eigen::Matrix3d::Identity(), 0.1, 0.04));  // the root link
  const urdf::Joint fixed = joint(urdf::Joint::FIXED, 0, 0, 1);
  EXPECT_FALSE(isWheelCylinder(&fixed, Eigen::Matrix3d::Identity(), 0.1, 0.04));
  const urdf::Joint prismatic = joint(urdf::Joint::PRISMATIC, 0, 0, 1);
  EXPECT_FALSE(isWheelCylinder(&prismatic, Eigen::Matrix3d::Identity(), 0.1, 0.04));
  const urdf::Joint tilted = joint(urdf::Joint::CONTINUOUS, 0, 0.01, 1);  // 10 mrad off the cylinder's axis
  EXPECT_FALSE(isWheelCylinder(&tilted, Eigen::Matrix3d::Identity(), 0.1, 0.04));
}

}  // namespace
}  // namespace servoloop::sim_common
