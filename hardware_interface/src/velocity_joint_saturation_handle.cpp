#include "servoloop/hardware_interface/velocity_joint_saturation_handle.hpp"

#include "joint_limits_handle_support.hpp"

namespace servoloop::hardware_interface {

VelocityJointSaturationHandle::VelocityJointSaturationHandle(const JointHandle& joint_handle,
                                                             const JointLimits& limits)
    : joint_handle_(joint_handle), limits_(limits) {
  detail::requireValidHandle(joint_handle_, limits_, "VelocityJointSaturationHandle");
  detail::requireVelocityLimits(joint_handle_, limits_, "VelocityJointSaturationHandle");
}

void VelocityJointSaturationHandle::enforceLimits(Duration period) noexcept {
  double lower = -limits_.max_velocity;
  double upper = limits_.max_velocity;
  if (limits_.has_acceleration_limits) {
    if (!has_previous_command_) previous_command_ = joint_handle_.getVelocity();
    const double max_step = limits_.max_acceleration * detail::periodSeconds(period.seconds);
    lower = std::max(previous_command_ - max_step, lower);
    upper = std::min(previous_command_ + max_step, upper);
  }

  const double command = detail::clampToBounds(detail::commandOr(joint_handle_, 0.0), lower, upper);
  joint_handle_.setCommand(command);
  previous_command_ = command;
  has_previous_command_ = true;
}

}  // namespace servoloop::hardware_interface
