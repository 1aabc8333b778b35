#pragma once
#include <string>

#include "servoloop/hardware_interface/joint_handle.hpp"
#include "servoloop/hardware_interface/joint_limits.hpp"
#include "servoloop/core/time.hpp"

namespace servoloop::hardware_interface {

// Saturates a joint's effort command to [-max_effort, max_effort], and stops it
// from pushing further out of the position range or faster than max_velocity:
// measured position below min_position (above max_position) makes the lower
// (upper) bound 0; measured velocity below -max_velocity (above max_velocity)
// does the same. Position and velocity limits are optional; the effort limit is
// required. A NaN command becomes 0 (always inside the bounds). Stateless.
class EffortJointSaturationHandle {
 public:
  static constexpr const char* kInterfaceName = "EffortJointSaturationInterface";

  // Non-real-time. Throws servoloop::Error naming the joint when limits has no
  // effort limit, servoloop::ConfigError when a limit is unusable (see
  // validateJointLimits).
  EffortJointSaturationHandle(const JointHandle& joint_handle, const JointLimits& limits);

  const std::string& getName() const { return joint_handle_.getName(); }

  // Real-time: no allocation, no throw. The period is not used.
  void enforceLimits(Duration period) noexcept;

 private:
  JointHandle joint_handle_;
  JointLimits limits_;
};

}  // namespace servoloop::hardware_interface
