#include "servoloop/sim_common/joint_command_limiter.hpp"

namespace servoloop::sim_common {

namespace hi = hardware_interface;

JointCommandLimiter::JointCommandLimiter(const std::string& joint_name,
                                         transmissions::JointValues& values,
                                         const transmissions::JointCommandInterfaces& offered,
                                         const hi::JointLimitsConfig* config) {
  if (config == nullptr) return;
  const hi::JointLimits& limits = config->limits;
  const std::optional<hi::SoftJointLimits>& soft = config->soft_limits;
  // Handles built straight on the storage: getting them from the command
  // interfaces would record claims as if a controller had asked.
  const hi::JointStateHandle state(joint_name, &values.position, &values.velocity, &values.effort);

  if (offered.effort) {
    const hi::JointHandle handle(state, &values.effort_command);
    if (soft && limits.has_velocity_limits && limits.has_effort_limits) {
      effort_soft_limits_.emplace(handle, limits, *soft);
    } else if (limits.has_effort_limits) {
      effort_saturation_.emplace(handle, limits);
    }
  }
  if (offered.velocity) {
    const hi::JointHandle handle(state, &values.velocity_command);
    if (soft && limits.has_velocity_limits) {
      velocity_soft_limits_.emplace(handle, limits, *soft);
    } else if (limits.has_velocity_limits) {
      velocity_saturation_.emplace(handle, limits);
    }
  }
  if (offered.position) {
    const hi::JointHandle handle(state, &values.position_command);
    if (soft && limits.has_velocity_limits) {
      position_soft_limits_.emplace(handle, limits, *soft);
    } else if (limits.has_position_limits || limits.has_velocity_limits) {
      position_saturation_.emplace(handle, limits);
    }
  }
}

void JointCommandLimiter::enforce(JointCommandMode mode, Duration period) noexcept {
  switch (mode) {
    case JointCommandMode::none:
      return;
    case JointCommandMode::effort:
      if (effort_soft_limits_) effort_soft_limits_->enforceLimits(period);
      else if (effort_saturation_) effort_saturation_->enforceLimits(period);
      return;
    case JointCommandMode::velocity:
      if (velocity_soft_limits_) velocity_soft_limits_->enforceLimits(period);
      else if (velocity_saturation_) velocity_saturation_->enforceLimits(period);
      return;
    case JointCommandMode::position:
      if (position_soft_limits_) position_soft_limits_->enforceLimits(period);
      else if (position_saturation_) position_saturation_->enforceLimits(period);
      return;
  }
}

void JointCommandLimiter::reset() noexcept {
  if (velocity_saturation_) velocity_saturation_->reset();
  if (position_saturation_) position_saturation_->reset();
  if (position_soft_limits_) position_soft_limits_->reset();
}

LimitEnforcement JointCommandLimiter::enforcement(JointCommandMode mode) const noexcept {
  switch (mode) {
    case JointCommandMode::none:
      return LimitEnforcement::none;
    case JointCommandMode::effort:
      return effort_soft_limits_ ? LimitEnforcement::soft_limits
             : effort_saturation_ ? LimitEnforcement::saturation
                                  : LimitEnforcement::none;
    case JointCommandMode::velocity:
      return velocity_soft_limits_ ? LimitEnforcement::soft_limits
             : velocity_saturation_ ? LimitEnforcement::saturation
                                    : LimitEnforcement::none;
    case JointCommandMode::position:
      return position_soft_limits_ ? LimitEnforcement::soft_limits
             : position_saturation_ ? LimitEnforcement::saturation
                                    : LimitEnforcement::none;
  }
  return LimitEnforcement::none;
}

}  // namespace servoloop::sim_common
