#pragma once
// How a position controller turns a joint setpoint and a measured position
// into an error, by URDF joint type, as ros_control's position controllers do:
//   revolute   - setpoint clamped to [lower, upper]; error = shortest angular
//                distance that stays inside the limits;
//   continuous - no clamping; error = shortest angular distance in [-π, π];
//   prismatic  - setpoint clamped to [lower, upper]; error = difference.
#include <algorithm>
#include <string>

#include <urdf_model/model.h>

namespace servoloop::controllers {

class JointPositionError {
 public:
  enum class Kind { revolute, continuous, prismatic, unknown };

  // Plain difference, no clamping (used when no robot model is known).
  JointPositionError() = default;

  // Non-real-time. Reads joint_name's type and position limits from the model
  // (through hardware_interface::getJointLimits). Throws servoloop::ConfigError
  // naming controller_name and the joint when the model has no such joint or
  // the joint is not revolute, continuous or prismatic.
  static JointPositionError fromModel(const urdf::ModelInterface& model, const std::string& joint_name,
                                      const std::string& controller_name);

  // Real-time. The setpoint inside the joint's position limits (unchanged for
  // joints without them).
  double clampSetpoint(double setpoint) const noexcept {
    if (!has_position_limits_) return setpoint;
    return std::min(std::max(setpoint, lower_), upper_);  // no UB if a model had lower > upper
  }
  // Real-time. setpoint - position, in the sense of the joint type above.
  // Inline for the common cases, which need no wrapping: prismatic joints,
  // and revolute joints whose limits span less than one turn while both
  // angles are inside them (then the only path that stays inside the limits
  // is the direct one).
  double error(double setpoint, double position) const noexcept {
    if (plain_difference_) return setpoint - position;
    if (within_one_turn_ && position >= lower_ && position <= upper_ && setpoint >= lower_ &&
        setpoint <= upper_) {
      return setpoint - position;
    }
    return wrappedError(setpoint, position);
  }

  Kind kind() const noexcept { return kind_; }
  bool hasPositionLimits() const noexcept { return has_position_limits_; }
  double lowerLimit() const noexcept { return lower_; }
  double upperLimit() const noexcept { return upper_; }

 private:
  // The general case: shortest angular distance, within the limits if any.
  double wrappedError(double setpoint, double position) const noexcept;

  Kind kind_ = Kind::unknown;
  bool plain_difference_ = true;   // prismatic or unknown: no wrapping ever
  bool within_one_turn_ = false;   // revolute with limits spanning less than 2π
  bool has_position_limits_ = false;
  double lower_ = 0.0;  // rad or m
  double upper_ = 0.0;
};

}  // namespace servoloop::controllers
