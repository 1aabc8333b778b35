#include "servoloop/hardware_interface/velocity_joint_soft_limits_handle.hpp"

#include "joint_limits_handle_support.hpp"
#include "servoloop/hardware_interface/joint_limits_validation.hpp"

namespace servoloop::hardware_interface {

VelocityJointSoftLimitsHandle::VelocityJointSoftLimitsHandle(const JointHandle& joint_handle,
                                                             const JointLimits& limits,
                                                             const SoftJointLimits& soft_limits)
    : joint_handle_(joint_handle), limits_(limits), soft_limits_(soft_limits) {
  detail::requireValidHandle(joint_handle_, limits_, "VelocityJointSoftLimitsHandle");
  detail::requireVelocityLimits(joint_handle_, limits_, "VelocityJointSoftLimitsHandle");
  validateSoftJointLimits(joint_handle_.getName(), soft_limits_);
}

void VelocityJointSoftLimitsHandle::enforceLimits(Duration period) noexcept {
  const double max_velocity = limits_.max_velocity;
  double lower = -max_velocity;
  double upper = max_velocity;
  if (limits_.has_position_limits) {
    const double position = joint_handle_.getPosition();
    lower = detail::clampToBounds(-soft_limits_.k_position * (position - soft_limits_.min_position),
                                  -max_velocity, max_velocity);
    upper = detail::clampToBounds(-soft_limits_.k_position * (position - soft_limits_.max_position),
                                  -max_velocity, max_velocity);
  }
  if (limits_.has_acceleration_limits) {
    const double velocity = joint_handle_.getVelocity();
    const double max_step = limits_.max_acceleration * detail::periodSeconds(period.seconds);
    lower = std::max(velocity - max_step, lower);
    upper = std::min(velocity + max_step, upper);
  }
  joint_handle_.setCommand(detail::clampToBounds(detail::commandOr(joint_handle_, 0.0), lower, upper));
}

}  // namespace servoloop::hardware_interface
