#pragma once
// How a position controller turns a joint setpoint and a measured position
// into an error, by URDF joint type, as ros_control's position controllers do:
//   revolute   - setpoint clamped to [lower, upper]; error = shortest angular
//                distance that stays inside the limits;
//   continuous - no clamping; error = shortest angular distance in [-π, π];
//   prismatic  - setpoint clamped to [lower, upper]; error = difference.
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
  double clampSetpoint(double setpoint) const noexcept;
  // Real-time. setpoint - position, in the sense of the joint type above.
  double error(double setpoint, double position) const noexcept;

  Kind kind() const noexcept { return kind_; }
  bool hasPositionLimits() const noexcept { return has_position_limits_; }
  double lowerLimit() const noexcept { return lower_; }
  double upperLimit() const noexcept { return upper_; }

 private:
  Kind kind_ = Kind::unknown;
  bool has_position_limits_ = false;
  double lower_ = 0.0;  // rad or m
  double upper_ = 0.0;
};

}  // namespace servoloop::controllers
