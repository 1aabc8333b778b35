#include "servoloop/controllers/common/joint_position_error.hpp"

#include <algorithm>
#include <numbers>

#include "servoloop/controllers/common/angles.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/joint_limits.hpp"
#include "servoloop/hardware_interface/joint_limits_urdf.hpp"

namespace servoloop::controllers {

JointPositionError JointPositionError::fromModel(const urdf::ModelInterface& model,
                                                 const std::string& joint_name,
                                                 const std::string& controller_name) {
  const urdf::JointConstSharedPtr joint = model.getJoint(joint_name);
  if (!joint) {
    throw ConfigError("controller '" + controller_name + "': joint '" + joint_name +
                      "' is not in the robot description (URDF '" + model.getName() +
                      "'); check the controller's joint name");
  }
  JointPositionError result;
  switch (joint->type) {
    case urdf::Joint::REVOLUTE: result.kind_ = Kind::revolute; break;
    case urdf::Joint::CONTINUOUS: result.kind_ = Kind::continuous; break;
    case urdf::Joint::PRISMATIC: result.kind_ = Kind::prismatic; break;
    default:
      throw ConfigError("controller '" + controller_name + "': joint '" + joint_name +
                        "' is not revolute, continuous or prismatic in the URDF; a position "
                        "controller cannot drive it");
  }
  hardware_interface::JointLimits limits;
  if (hardware_interface::getJointLimits(*joint, limits) && limits.has_position_limits &&
      result.kind_ != Kind::continuous) {
    result.has_position_limits_ = true;
    result.lower_ = limits.min_position;
    result.upper_ = limits.max_position;
  }
  result.plain_difference_ = result.kind_ == Kind::prismatic;
  result.within_one_turn_ = result.kind_ == Kind::revolute && result.has_position_limits_ &&
                            result.upper_ - result.lower_ < 2.0 * std::numbers::pi;
  return result;
}

double JointPositionError::wrappedError(double setpoint, double position) const noexcept {
  switch (kind_) {
    case Kind::revolute:
      if (has_position_limits_) {
        return shortestAngularDistanceWithinLimits(position, setpoint, lower_, upper_);
      }
      return shortestAngularDistance(position, setpoint);
    case Kind::continuous: return shortestAngularDistance(position, setpoint);
    case Kind::prismatic:
    case Kind::unknown: break;
  }
  return setpoint - position;
}

}  // namespace servoloop::controllers
