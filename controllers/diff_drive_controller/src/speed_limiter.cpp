#include "servoloop/controllers/diff_drive_controller/speed_limiter.hpp"

#include <algorithm>

#include "servoloop/controllers/common/controller_params.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::controllers::diff_drive_controller {
namespace {

// One limit pair: max (default 0) and min (default −max); min <= max.
void bounds(const controller_manager::ControllerContext& context, const std::string& prefix, const char* what,
            double& min, double& max) {
  max = optionalNumber(context, prefix + "/max_" + what, 0.0);
  min = optionalNumber(context, prefix + "/min_" + what, -max);
  if (min > max) {
    throw ConfigError("controller '" + context.name + "': parameter '" +
                      parameterPath(context, prefix + "/min_" + what) + "' (" + std::to_string(min) +
                      ") is above max_" + what + " (" + std::to_string(max) + ")");
  }
}

}  // namespace

SpeedLimiter SpeedLimiter::fromParams(const controller_manager::ControllerContext& context, const std::string& prefix) {
  SpeedLimiter limiter;
  limiter.has_velocity_limits = optionalBool(context, prefix + "/has_velocity_limits", false);
  limiter.has_acceleration_limits = optionalBool(context, prefix + "/has_acceleration_limits", false);
  limiter.has_jerk_limits = optionalBool(context, prefix + "/has_jerk_limits", false);
  bounds(context, prefix, "velocity", limiter.min_velocity, limiter.max_velocity);
  bounds(context, prefix, "acceleration", limiter.min_acceleration, limiter.max_acceleration);
  bounds(context, prefix, "jerk", limiter.min_jerk, limiter.max_jerk);
  return limiter;
}

void SpeedLimiter::limit(double& v, double v0, double v1, double dt) const noexcept {
  if (has_jerk_limits) {
    const double dv = v - v0;
    const double dv0 = v0 - v1;
    const double dt2 = 2.0 * dt * dt;
    const double da = std::clamp(dv - dv0, min_jerk * dt2, max_jerk * dt2);
    v = v0 + dv0 + da;
  }
  if (has_acceleration_limits) {
    const double dv = std::clamp(v - v0, min_acceleration * dt, max_acceleration * dt);
    v = v0 + dv;
  }
  if (has_velocity_limits) v = std::clamp(v, min_velocity, max_velocity);
}

}  // namespace servoloop::controllers::diff_drive_controller
