#pragma once
#include <string>

#include "servoloop/hardware_interface/joint_handle.hpp"
#include "servoloop/hardware_interface/joint_limits.hpp"
#include "servoloop/core/time.hpp"

namespace servoloop::hardware_interface {

// Saturates a joint's position command to [min_position, max_position] and,
// with a velocity limit, to within max_velocity·period of the previous
// (limited) command:
//   [max(prev - max_velocity·dt, min_position), min(prev + max_velocity·dt, max_position)]
// where prev starts as the measured position (after construction and reset()).
// When prev lies beyond a position limit the bounds cross and the position
// limit wins. A NaN command holds prev. Needs position or velocity limits.
class PositionJointSaturationHandle {
 public:
  static constexpr const char* kInterfaceName = "PositionJointSaturationInterface";

  // Non-real-time. Throws servoloop::Error naming the joint when limits has
  // neither position nor velocity limits, servoloop::ConfigError when a value
  // is unusable.
  PositionJointSaturationHandle(const JointHandle& joint_handle, const JointLimits& limits);

  const std::string& getName() const { return joint_handle_.getName(); }

  // Real-time: no allocation, no throw. period: time since the previous call
  // (negative counts as 0).
  void enforceLimits(Duration period) noexcept;

  // Real-time safe. Forget the previous command: the next enforceLimits starts
  // from the measured position. Call when the controller writing this joint starts.
  void reset() noexcept { has_previous_command_ = false; }

 private:
  JointHandle joint_handle_;
  JointLimits limits_;
  double min_position_;  // -inf without position limits
  double max_position_;  // +inf without position limits
  double previous_command_ = 0.0;
  bool has_previous_command_ = false;
};

}  // namespace servoloop::hardware_interface
