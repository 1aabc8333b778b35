#include "servoloop/hardware_interface/effort_joint_saturation_handle.hpp"

#include "joint_limits_handle_support.hpp"

namespace servoloop::hardware_interface {

EffortJointSaturationHandle::EffortJointSaturationHandle(const JointHandle& joint_handle,
                                                         const JointLimits& limits)
    : joint_handle_(joint_handle), limits_(limits) {
  detail::requireValidHandle(joint_handle_, limits_, "EffortJointSaturationHandle");
  detail::requireEffortLimits(joint_handle_, limits_, "EffortJointSaturationHandle");
}

void EffortJointSaturationHandle::enforceLimits(Duration /*period*/) noexcept {
  double min_effort = -limits_.max_effort;
  double max_effort = limits_.max_effort;

  // Beyond a position limit: allow only effort that pushes back inside.
  if (limits_.has_position_limits) {
    const double position = joint_handle_.getPosition();
    if (position < limits_.min_position) {
      min_effort = 0.0;
    } else if (position > limits_.max_position) {
      max_effort = 0.0;
    }
  }
  // Faster than the velocity limit: allow only effort that slows the joint.
  if (limits_.has_velocity_limits) {
    const double velocity = joint_handle_.getVelocity();
    if (velocity < -limits_.max_velocity) {
      min_effort = 0.0;
    } else if (velocity > limits_.max_velocity) {
      max_effort = 0.0;
    }
  }
  joint_handle_.setCommand(
      detail::clampToBounds(detail::commandOr(joint_handle_, 0.0), min_effort, max_effort));
}

}  // namespace servoloop::hardware_interface
