#pragma once
// A joint's limits, in joint space: rad or m, rad/s or m/s, rad/s² or m/s²,
// N·m or N. Plain data, filled from the URDF <limit> element and overridden by
// the YAML under <robot ns>/joint_limits/<joint> (joint_limits_urdf.hpp,
// joint_limits_yaml.hpp), then handed to the enforcement handles.
#include "servoloop/hardware_interface/soft_joint_limits.hpp"

namespace servoloop::hardware_interface {

struct JointLimits {
  // Only meaningful when the matching has_… flag is true.
  bool has_position_limits = false;
  double min_position = 0.0;
  double max_position = 0.0;

  bool has_velocity_limits = false;
  double max_velocity = 0.0;  // magnitude: the joint may move in [-max, max]

  bool has_acceleration_limits = false;
  double max_acceleration = 0.0;  // magnitude

  bool has_effort_limits = false;
  double max_effort = 0.0;  // magnitude

  // The joint position is an angle that wraps (continuous joints); such a joint
  // has no position limits.
  bool angle_wraparound = false;
};

}  // namespace servoloop::hardware_interface
