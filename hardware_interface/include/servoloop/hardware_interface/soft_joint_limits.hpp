#pragma once
// Soft limits of a joint (the URDF <safety_controller> element): a position band
// inside the hard limits and the gains that push the joint back into it.

namespace servoloop::hardware_interface {

struct SoftJointLimits {
  double min_position = 0.0;  // URDF soft_lower_limit, rad or m
  double max_position = 0.0;  // URDF soft_upper_limit, rad or m
  // Position gain: the velocity bound per unit of position beyond a soft limit
  // (1/s). Velocity gain: the effort bound per unit of velocity beyond the
  // velocity bound (N·m·s/rad or N·s/m).
  double k_position = 0.0;
  double k_velocity = 0.0;
};

}  // namespace servoloop::hardware_interface
