#pragma once
// Wheels on the ground. A URDF wheel is a cylinder, and a rigid cylinder lying
// level touches a plane along a line. Both engines reduce that line to points
// at its ends (the rims), chosen by which rim is a hair lower: a pair of wheels
// then turns about a point off the axle's centre, or scrubs, and a diff drive's
// odometry disagrees with the simulated motion by a few per cent. A real tyre
// touches in its middle plane. So a cylinder that is a wheel gets a tyre's
// profile for contacts, flat tread rounded over the full width, touching the
// ground in the middle plane at the URDF radius: bullet rounds the cylinder's
// edges with a radius of half its length; mujoco uses the ellipsoid of the
// same radius and half length. Other cylinders keep their shape.
#include <Eigen/Core>
#include <urdf_model/joint.h>

namespace servoloop::sim_common {

// True when the cylinder (radius, length, axis along its own z) on a link is a
// wheel: the link's parent joint is revolute or continuous about the
// cylinder's axis (`cylinder_in_link`: the collision's rotation in the link
// frame, which is the joint frame), and the cylinder is no wider than its
// radius (a roller or a drum is not a wheel).
bool isWheelCylinder(const urdf::Joint* parent_joint, const Eigen::Matrix3d& cylinder_in_link, double radius,
                     double length);

}  // namespace servoloop::sim_common
