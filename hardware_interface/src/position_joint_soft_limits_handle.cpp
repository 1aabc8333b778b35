#include "servoloop/hardware_interface/position_joint_soft_limits_handle.hpp"

#include "joint_limits_handle_support.hpp"
#include "servoloop/hardware_interface/joint_limits_validation.hpp"

namespace servoloop::hardware_interface {

PositionJointSoftLimitsHandle::PositionJointSoftLimitsHandle(const JointHandle& joint_handle,
                                                             const JointLimits& limits,
                                                             const SoftJointLimits& soft_limits)
    : joint_handle_(joint_handle), limits_(limits), soft_limits_(soft_limits) {
  detail::requireValidHandle(joint_handle_, limits_, "PositionJointSoftLimitsHandle");
  detail::requireVelocityLimits(joint_handle_, limits_, "PositionJointSoftLimitsHandle");
  validateSoftJointLimits(joint_handle_.getName(), soft_limits_);
}

void PositionJointSoftLimitsHandle::enforceLimits(Duration period) noexcept {
  if (!has_previous_command_) {
    previous_command_ = joint_handle_.getPosition();
    has_previous_command_ = true;
  }
  const double dt = detail::periodSeconds(period.seconds);
  const double max_velocity = limits_.max_velocity;

  // Velocity bounds from the distance of the previous command to the soft limits.
  double min_velocity = -max_velocity;
  double max_velocity_bound = max_velocity;
  if (limits_.has_position_limits) {
    min_velocity = detail::clampToBounds(
        -soft_limits_.k_position * (previous_command_ - soft_limits_.min_position), -max_velocity,
        max_velocity);
    max_velocity_bound = detail::clampToBounds(
        -soft_limits_.k_position * (previous_command_ - soft_limits_.max_position), -max_velocity,
        max_velocity);
  }

  // Position bounds: one period at those velocities, inside the hard limits.
  double lower = previous_command_ + min_velocity * dt;
  double upper = previous_command_ + max_velocity_bound * dt;
  if (limits_.has_position_limits) {
    lower = std::max(lower, limits_.min_position);
    upper = std::min(upper, limits_.max_position);
  }

  const double command =
      detail::clampToBounds(detail::commandOr(joint_handle_, previous_command_), lower, upper);
  joint_handle_.setCommand(command);
  previous_command_ = command;
}

}  // namespace servoloop::hardware_interface
