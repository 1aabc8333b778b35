#include "servoloop/hardware_interface/position_joint_saturation_handle.hpp"

#include <limits>

#include "joint_limits_handle_support.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::hardware_interface {

PositionJointSaturationHandle::PositionJointSaturationHandle(const JointHandle& joint_handle,
                                                             const JointLimits& limits)
    : joint_handle_(joint_handle),
      limits_(limits),
      min_position_(limits.has_position_limits ? limits.min_position
                                               : -std::numeric_limits<double>::infinity()),
      max_position_(limits.has_position_limits ? limits.max_position
                                               : std::numeric_limits<double>::infinity()) {
  detail::requireValidHandle(joint_handle_, limits_, "PositionJointSaturationHandle");
  if (!limits_.has_position_limits && !limits_.has_velocity_limits) {
    const std::string& joint = joint_handle_.getName();
    throw Error("joint '" + joint +
                "': PositionJointSaturationHandle needs position or velocity limits; add "
                "lower/upper/velocity to the joint's URDF <limit> or has_position_limits or "
                "has_velocity_limits under joint_limits/" + joint);
  }
}

void PositionJointSaturationHandle::enforceLimits(Duration period) noexcept {
  if (!has_previous_command_) {
    previous_command_ = joint_handle_.getPosition();
    has_previous_command_ = true;
  }

  double lower = min_position_;
  double upper = max_position_;
  if (limits_.has_velocity_limits) {
    const double max_step = limits_.max_velocity * detail::periodSeconds(period.seconds);
    lower = std::max(previous_command_ - max_step, lower);
    upper = std::min(previous_command_ + max_step, upper);
  }

  const double command =
      detail::clampToBounds(detail::commandOr(joint_handle_, previous_command_), lower, upper);
  joint_handle_.setCommand(command);
  previous_command_ = command;
}

}  // namespace servoloop::hardware_interface
