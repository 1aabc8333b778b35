#pragma once
#include <string>

#include "servoloop/hardware_interface/joint_handle.hpp"
#include "servoloop/hardware_interface/joint_limits.hpp"
#include "servoloop/hardware_interface/soft_joint_limits.hpp"
#include "servoloop/core/time.hpp"

namespace servoloop::hardware_interface {

// Soft limits on a joint's effort command (ros_control's
// EffortJointSoftLimitsHandle), from the measured position p and velocity v:
//   v_lo = clamp(-k_position·(p - soft_min), -max_velocity, max_velocity)
//   v_hi = clamp(-k_position·(p - soft_max), -max_velocity, max_velocity)
//   e_lo = clamp(-k_velocity·(v - v_lo), -max_effort, max_effort)
//   e_hi = clamp(-k_velocity·(v - v_hi), -max_effort, max_effort)
// and the command is clamped to [e_lo, e_hi]. As in ros_control, the position
// terms apply only when the joint has (hard) position limits; without them
// v_lo, v_hi = -max_velocity, max_velocity. Velocity and effort limits are
// required. A NaN command becomes 0, then is clamped. Stateless.
class EffortJointSoftLimitsHandle {
 public:
  static constexpr const char* kInterfaceName = "EffortJointSoftLimitsInterface";

  // Non-real-time. Throws servoloop::Error naming the joint when a required
  // limit is missing, servoloop::ConfigError when a value is unusable.
  EffortJointSoftLimitsHandle(const JointHandle& joint_handle, const JointLimits& limits,
                              const SoftJointLimits& soft_limits);

  const std::string& getName() const { return joint_handle_.getName(); }

  // Real-time: no allocation, no throw. The period is not used.
  void enforceLimits(Duration period) noexcept;

 private:
  JointHandle joint_handle_;
  JointLimits limits_;
  SoftJointLimits soft_limits_;
};

}  // namespace servoloop::hardware_interface
