#pragma once
// Joint limits read from a URDF joint (urdfdom), as ros_control reads them.
// Non-real-time.
#include <urdf_model/joint.h>

#include "servoloop/hardware_interface/joint_limits.hpp"
#include "servoloop/hardware_interface/soft_joint_limits.hpp"

namespace servoloop::hardware_interface {

// Overwrites the groups the URDF joint defines and leaves the others as they are:
//  - revolute/prismatic with <limit>: position limits [lower, upper];
//  - continuous: no position limits, angle_wraparound = true;
//  - any joint with <limit>: velocity limit `velocity` and effort limit `effort`
//    (urdfdom requires both attributes), and no acceleration limit (URDF has none).
// Returns false (limits untouched) when the joint gives nothing: a fixed,
// floating or planar joint, or a revolute/prismatic one without <limit>.
// Unlike ros_control, a continuous joint without <limit> still reports its wrap
// around (ros_control returned false for it and left angle_wraparound unset).
bool getJointLimits(const urdf::Joint& joint, JointLimits& limits);

// Soft limits from <safety_controller soft_lower_limit soft_upper_limit
// k_position k_velocity>. Returns false (soft_limits untouched) when the joint
// has no <safety_controller>.
bool getSoftJointLimits(const urdf::Joint& joint, SoftJointLimits& soft_limits);

}  // namespace servoloop::hardware_interface
