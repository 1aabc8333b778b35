#include "servoloop/hardware_interface/effort_joint_soft_limits_handle.hpp"

#include "joint_limits_handle_support.hpp"
#include "servoloop/hardware_interface/joint_limits_validation.hpp"

namespace servoloop::hardware_interface {

EffortJointSoftLimitsHandle::EffortJointSoftLimitsHandle(const JointHandle& joint_handle,
                                                         const JointLimits& limits,
                                                         const SoftJointLimits& soft_limits)
    : joint_handle_(joint_handle), limits_(limits), soft_limits_(soft_limits) {
  detail::requireValidHandle(joint_handle_, limits_, "EffortJointSoftLimitsHandle");
  detail::requireVelocityLimits(joint_handle_, limits_, "EffortJointSoftLimitsHandle");
  detail::requireEffortLimits(joint_handle_, limits_, "EffortJointSoftLimitsHandle");
  validateSoftJointLimits(joint_handle_.getName(), soft_limits_);
}

void EffortJointSoftLimitsHandle::enforceLimits(Duration /*period*/) noexcept {
  const double max_velocity = limits_.max_velocity;
  const double max_effort = limits_.max_effort;

  // Velocity bounds: shrink towards (and past) zero as the joint nears and
  // crosses a soft position limit.
  double min_velocity = -max_velocity;
  double max_velocity_bound = max_velocity;
  if (limits_.has_position_limits) {
    const double position = joint_handle_.getPosition();
    min_velocity = detail::clampToBounds(-soft_limits_.k_position * (position - soft_limits_.min_position),
                                         -max_velocity, max_velocity);
    max_velocity_bound = detail::clampToBounds(
        -soft_limits_.k_position * (position - soft_limits_.max_position), -max_velocity, max_velocity);
  }

  // Effort bounds: a velocity outside [min_velocity, max_velocity_bound] is
  // pushed back with gain k_velocity.
  const double velocity = joint_handle_.getVelocity();
  const double min_effort = detail::clampToBounds(-soft_limits_.k_velocity * (velocity - min_velocity),
                                                  -max_effort, max_effort);
  const double max_effort_bound = detail::clampToBounds(
      -soft_limits_.k_velocity * (velocity - max_velocity_bound), -max_effort, max_effort);

  joint_handle_.setCommand(
      detail::clampToBounds(detail::commandOr(joint_handle_, 0.0), min_effort, max_effort_bound));
}

}  // namespace servoloop::hardware_interface
