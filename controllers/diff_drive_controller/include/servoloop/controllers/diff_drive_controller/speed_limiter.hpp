#pragma once
// Limits a velocity command (one axis of a mobile base: linear x or angular
// z) to velocity, acceleration and jerk bounds, as ros_controllers'
// diff_drive_controller does, read from `<prefix>/has_velocity_limits`,
// `max_velocity`, `min_velocity` (default −max), and the same for
// acceleration and jerk. Real-time safe apart from the reading.
#include <string>

#include "servoloop/controller_manager/controller_context.hpp"

namespace servoloop::controllers::diff_drive_controller {

struct SpeedLimiter {
  bool has_velocity_limits = false;
  bool has_acceleration_limits = false;
  bool has_jerk_limits = false;
  double min_velocity = 0.0, max_velocity = 0.0;          // m/s or rad/s
  double min_acceleration = 0.0, max_acceleration = 0.0;  // per s
  double min_jerk = 0.0, max_jerk = 0.0;                  // per s²

  // Non-real-time. prefix: e.g. "linear/x". Throws servoloop::ConfigError
  // naming the parameter (a limit that is not a number, min > max).
  static SpeedLimiter fromParams(const controller_manager::ControllerContext& context, const std::string& prefix);

  // Real-time. v: the command, limited in place; v0, v1: the commands of the
  // last two cycles; dt: the period. Jerk first, then acceleration, then
  // velocity, as ros_controllers.
  void limit(double& v, double v0, double v1, double dt) const noexcept;
};

}  // namespace servoloop::controllers::diff_drive_controller
