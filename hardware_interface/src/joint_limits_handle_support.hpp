#pragma once
// Private helpers shared by the joint limits enforcement handles.
#include <algorithm>
#include <cmath>

#include "servoloop/hardware_interface/joint_handle.hpp"
#include "servoloop/hardware_interface/joint_limits.hpp"

namespace servoloop::hardware_interface::detail {

// min(max(value, lower), upper). When the bounds cross (a rate bound around a
// previous command that lies beyond a position limit), the upper bound wins,
// as in ros_control. Unlike std::clamp this is defined for crossed bounds.
// A NaN value passes through: callers replace NaN commands first.
inline double clampToBounds(double value, double lower, double upper) {
  return std::min(std::max(value, lower), upper);
}

// The command to limit: the one written, or `fallback` when it is NaN.
inline double commandOr(const JointHandle& joint_handle, double fallback) {
  const double command = joint_handle.getCommand();
  return std::isnan(command) ? fallback : command;
}

// A period the rate bounds can use: negative periods count as zero.
inline double periodSeconds(double seconds) { return seconds > 0.0 ? seconds : 0.0; }

// Constructor checks; they throw servoloop::Error naming the joint, the handle
// and how to add what is missing. requireValidHandle also runs
// validateJointLimits (servoloop::ConfigError).
void requireValidHandle(const JointHandle& joint_handle, const JointLimits& limits,
                        const char* handle_kind);
void requireVelocityLimits(const JointHandle& joint_handle, const JointLimits& limits,
                           const char* handle_kind);
void requireEffortLimits(const JointHandle& joint_handle, const JointLimits& limits,
                         const char* handle_kind);

}  // namespace servoloop::hardware_interface::detail
