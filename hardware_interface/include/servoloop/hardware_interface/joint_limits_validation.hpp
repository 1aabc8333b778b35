#pragma once
// Checks that limits can be enforced as written, whatever their source (URDF,
// YAML, code). Non-real-time.
#include <string>

#include "servoloop/hardware_interface/joint_limits.hpp"
#include "servoloop/hardware_interface/soft_joint_limits.hpp"

namespace servoloop::hardware_interface {

// Throws servoloop::ConfigError naming the joint and the value when a limit that
// is switched on is NaN, a magnitude (max_velocity, max_acceleration, max_effort)
// is negative, or min_position > max_position.
void validateJointLimits(const std::string& joint_name, const JointLimits& limits);

// Throws servoloop::ConfigError naming the joint when a value is NaN, a gain is
// negative, or soft_lower_limit > soft_upper_limit.
void validateSoftJointLimits(const std::string& joint_name, const SoftJointLimits& soft_limits);

}  // namespace servoloop::hardware_interface
