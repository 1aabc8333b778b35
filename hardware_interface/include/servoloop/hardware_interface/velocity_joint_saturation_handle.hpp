#pragma once
#include <string>

#include "servoloop/hardware_interface/joint_handle.hpp"
#include "servoloop/hardware_interface/joint_limits.hpp"
#include "servoloop/core/time.hpp"

namespace servoloop::hardware_interface {

// Saturates a joint's velocity command to [-max_velocity, max_velocity] and,
// with an acceleration limit, to within max_acceleration·period of the previous
// (limited) command:
//   [max(prev - max_acceleration·dt, -max_velocity), min(prev + max_acceleration·dt, max_velocity)]
// prev starts as the measured velocity (after construction and reset());
// ros_control started it at 0. A NaN command becomes 0, then is clamped (so the
// joint slows down as fast as allowed). Needs a velocity limit.
class VelocityJointSaturationHandle {
 public:
  static constexpr const char* kInterfaceName = "VelocityJointSaturationInterface";

  // Non-real-time. Throws servoloop::Error naming the joint when limits has no
  // velocity limit, servoloop::ConfigError when a value is unusable.
  VelocityJointSaturationHandle(const JointHandle& joint_handle, const JointLimits& limits);

  const std::string& getName() const { return joint_handle_.getName(); }

  // Real-time: no allocation, no throw. period: time since the previous call
  // (negative counts as 0).
  void enforceLimits(Duration period) noexcept;

  // Real-time safe. Forget the previous command: the next enforceLimits starts
  // from the measured velocity.
  void reset() noexcept { has_previous_command_ = false; }

 private:
  JointHandle joint_handle_;
  JointLimits limits_;
  double previous_command_ = 0.0;
  bool has_previous_command_ = false;
};

}  // namespace servoloop::hardware_interface
