#pragma once
// All joint limits of one robot: the URDF's, overridden by the YAML under the
// robot namespace's joint_limits: map. Non-real-time; run at configure time,
// then build the enforcement handles from the result.
#include <map>
#include <optional>
#include <string>

#include <urdf_model/model.h>
#include <yaml-cpp/yaml.h>

#include "servoloop/hardware_interface/joint_limits.hpp"
#include "servoloop/hardware_interface/soft_joint_limits.hpp"

namespace servoloop::hardware_interface {

// The limits of one joint.
struct JointLimitsConfig {
  JointLimits limits;
  std::optional<SoftJointLimits> soft_limits;  // empty: no soft limits
};

// Joint name → limits, for every revolute, prismatic and continuous joint.
using RobotJointLimits = std::map<std::string, JointLimitsConfig>;

// model: the robot's URDF. robot_ns_node: the map of the robot namespace (the
// value of `one_DOF_robot:` in a controller YAML); it may lack joint_limits:
// or be undefined, and then the URDF alone decides. source_name (e.g. the YAML
// file's name) starts every error message when not empty.
// Throws servoloop::ConfigError for a bad key or type (see joint_limits_yaml.hpp),
// for a joint_limits entry naming no movable joint of the model, and for limits
// validateJointLimits/validateSoftJointLimits refuse.
RobotJointLimits loadRobotJointLimits(const urdf::ModelInterface& model,
                                      const YAML::Node& robot_ns_node,
                                      const std::string& source_name = "");

}  // namespace servoloop::hardware_interface
