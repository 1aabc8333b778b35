#pragma once
#include <string>

#include "servoloop/hardware_interface/joint_handle.hpp"
#include "servoloop/hardware_interface/joint_limits.hpp"
#include "servoloop/hardware_interface/soft_joint_limits.hpp"
#include "servoloop/core/time.hpp"

namespace servoloop::hardware_interface {

// Soft limits on a joint's position command (ros_control's
// PositionJointSoftLimitsHandle). From the previous (limited) command prev:
//   v_lo = clamp(-k_position·(prev - soft_min), -max_velocity, max_velocity)
//   v_hi = clamp(-k_position·(prev - soft_max), -max_velocity, max_velocity)
//   bounds [prev + v_lo·dt, prev + v_hi·dt], then within [min_position, max_position]
// prev starts as the measured position (after construction and reset()). As in
// ros_control, the soft terms apply only when the joint has (hard) position
// limits; without them v_lo, v_hi = -max_velocity, max_velocity. Needs a
// velocity limit. A NaN command holds prev (then the bounds apply).
class PositionJointSoftLimitsHandle {
 public:
  static constexpr const char* kInterfaceName = "PositionJointSoftLimitsInterface";

  // Non-real-time. Throws servoloop::Error naming the joint when limits has no
  // velocity limit, servoloop::ConfigError when a value is unusable.
  PositionJointSoftLimitsHandle(const JointHandle& joint_handle, const JointLimits& limits,
                                const SoftJointLimits& soft_limits);

  const std::string& getName() const { return joint_handle_.getName(); }

  // Real-time: no allocation, no throw. period: time since the previous call
  // (negative counts as 0).
  void enforceLimits(Duration period) noexcept;

  // Real-time safe. The next enforceLimits starts from the measured position.
  void reset() noexcept { has_previous_command_ = false; }

 private:
  JointHandle joint_handle_;
  JointLimits limits_;
  SoftJointLimits soft_limits_;
  double previous_command_ = 0.0;
  bool has_previous_command_ = false;
};

}  // namespace servoloop::hardware_interface
