#include "servoloop/hardware_interface/joint_limits_urdf.hpp"

namespace servoloop::hardware_interface {

bool getJointLimits(const urdf::Joint& joint, JointLimits& limits) {
  const bool has_range = joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::PRISMATIC;
  const bool wraps = joint.type == urdf::Joint::CONTINUOUS;
  if (!wraps && !(has_range && joint.limits)) return false;

  if (wraps) {
    limits.has_position_limits = false;
    limits.angle_wraparound = true;
  } else {
    limits.has_position_limits = true;
    limits.min_position = joint.limits->lower;
    limits.max_position = joint.limits->upper;
    limits.angle_wraparound = false;
  }
  if (joint.limits) {
    limits.has_velocity_limits = true;
    limits.max_velocity = joint.limits->velocity;
    limits.has_effort_limits = true;
    limits.max_effort = joint.limits->effort;
    limits.has_acceleration_limits = false;
  }
  return true;
}

bool getSoftJointLimits(const urdf::Joint& joint, SoftJointLimits& soft_limits) {
  if (!joint.safety) return false;
  soft_limits.min_position = joint.safety->soft_lower_limit;
  soft_limits.max_position = joint.safety->soft_upper_limit;
  soft_limits.k_position = joint.safety->k_position;
  soft_limits.k_velocity = joint.safety->k_velocity;
  return true;
}

}  // namespace servoloop::hardware_interface
