#pragma once
#include <string>

#include "servoloop/hardware_interface/joint_handle.hpp"
#include "servoloop/hardware_interface/joint_limits.hpp"
#include "servoloop/hardware_interface/soft_joint_limits.hpp"
#include "servoloop/core/time.hpp"

namespace servoloop::hardware_interface {

// Soft limits on a joint's velocity command (ros_control's
// VelocityJointSoftLimitsHandle), from the measured position p and velocity v:
//   v_lo = clamp(-k_position·(p - soft_min), -max_velocity, max_velocity)
//   v_hi = clamp(-k_position·(p - soft_max), -max_velocity, max_velocity)
// (as in ros_control only with hard position limits; otherwise ±max_velocity),
// and with an acceleration limit also within v ± max_acceleration·dt; the
// command is clamped to [v_lo, v_hi]. Needs a velocity limit. A NaN command
// becomes 0, then is clamped. Stateless.
class VelocityJointSoftLimitsHandle {
 public:
  static constexpr const char* kInterfaceName = "VelocityJointSoftLimitsInterface";

  // Non-real-time. Throws servoloop::Error naming the joint when limits has no
  // velocity limit, servoloop::ConfigError when a value is unusable.
  VelocityJointSoftLimitsHandle(const JointHandle& joint_handle, const JointLimits& limits,
                                const SoftJointLimits& soft_limits);

  const std::string& getName() const { return joint_handle_.getName(); }

  // Real-time: no allocation, no throw. period: time since the previous call
  // (negative counts as 0).
  void enforceLimits(Duration period) noexcept;

 private:
  JointHandle joint_handle_;
  JointLimits limits_;
  SoftJointLimits soft_limits_;
};

}  // namespace servoloop::hardware_interface
