#include "servoloop/hardware_interface/joint_limits_validation.hpp"

#include <cmath>

#include "servoloop/core/errors.hpp"

namespace servoloop::hardware_interface {
namespace {

std::string number(double value) {
  std::string text = std::to_string(value);
  // std::to_string prints six decimals; drop the trailing zeros for readability.
  if (text.find('.') != std::string::npos) {
    text.erase(text.find_last_not_of('0') + 1);
    if (text.back() == '.') text.pop_back();
  }
  return text;
}

void requireNumber(const std::string& joint_name, const char* what, double value) {
  if (std::isnan(value)) {
    throw ConfigError("joint '" + joint_name + "': " + what + " is NaN; give it a number");
  }
}

void requireMagnitude(const std::string& joint_name, const char* what, double value) {
  requireNumber(joint_name, what, value);
  if (value < 0.0) {
    throw ConfigError("joint '" + joint_name + "': " + what + " is " + number(value) +
                      "; it is a magnitude and must be >= 0");
  }
}

void requireOrdered(const std::string& joint_name, const char* lower_name, double lower,
                    const char* upper_name, double upper) {
  requireNumber(joint_name, lower_name, lower);
  requireNumber(joint_name, upper_name, upper);
  if (lower > upper) {
    throw ConfigError("joint '" + joint_name + "': " + lower_name + " " + number(lower) +
                      " is above " + upper_name + " " + number(upper) + "; swap them");
  }
}

}  // namespace

void validateJointLimits(const std::string& joint_name, const JointLimits& limits) {
  if (limits.has_position_limits) {
    requireOrdered(joint_name, "min_position", limits.min_position, "max_position",
                   limits.max_position);
  }
  if (limits.has_velocity_limits) requireMagnitude(joint_name, "max_velocity", limits.max_velocity);
  if (limits.has_acceleration_limits) {
    requireMagnitude(joint_name, "max_acceleration", limits.max_acceleration);
  }
  if (limits.has_effort_limits) requireMagnitude(joint_name, "max_effort", limits.max_effort);
}

void validateSoftJointLimits(const std::string& joint_name, const SoftJointLimits& soft_limits) {
  requireOrdered(joint_name, "soft_lower_limit", soft_limits.min_position, "soft_upper_limit",
                 soft_limits.max_position);
  requireMagnitude(joint_name, "k_position", soft_limits.k_position);
  requireMagnitude(joint_name, "k_velocity", soft_limits.k_velocity);
}

}  // namespace servoloop::hardware_interface
