#include "servoloop/hardware_interface/joint_limits_loader.hpp"

#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/joint_limits_urdf.hpp"
#include "servoloop/hardware_interface/joint_limits_validation.hpp"
#include "servoloop/hardware_interface/joint_limits_yaml.hpp"

namespace servoloop::hardware_interface {
namespace {

bool isMovable(const urdf::Joint& joint) {
  return joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::PRISMATIC ||
         joint.type == urdf::Joint::CONTINUOUS;
}

RobotJointLimits load(const urdf::ModelInterface& model, const YAML::Node& robot_ns_node) {
  RobotJointLimits result;
  for (const auto& [name, joint] : model.joints_) {
    if (!joint || !isMovable(*joint)) continue;
    JointLimitsConfig& config = result[name];
    getJointLimits(*joint, config.limits);
    SoftJointLimits soft;
    if (getSoftJointLimits(*joint, soft)) config.soft_limits = soft;
  }

  // Copy-initialised: yaml-cpp cannot assign a node read from a missing key.
  const YAML::Node joint_limits_node = robot_ns_node.IsDefined() && robot_ns_node.IsMap()
                                           ? robot_ns_node["joint_limits"]
                                           : YAML::Node();
  if (joint_limits_node.IsDefined() && !joint_limits_node.IsNull()) {
    if (!joint_limits_node.IsMap()) {
      throw ConfigError("joint_limits: expected a map from joint name to limits");
    }
    for (const auto& entry : joint_limits_node) {
      const std::string joint_name = entry.first.as<std::string>();
      auto it = result.find(joint_name);
      if (it == result.end()) {
        std::string known;
        for (const auto& [name, config] : result) known += (known.empty() ? "" : ", ") + name;
        throw ConfigError("joint_limits/" + joint_name + ": the URDF of robot '" + model.getName() +
                          "' has no revolute, prismatic or continuous joint of that name (it has: " +
                          (known.empty() ? "none" : known) + "); fix the joint name");
      }
      getJointLimits(entry.second, joint_name, it->second.limits);
      getSoftJointLimits(entry.second, joint_name, it->second.soft_limits);
    }
  }

  for (const auto& [name, config] : result) {
    validateJointLimits(name, config.limits);
    if (config.soft_limits) validateSoftJointLimits(name, *config.soft_limits);
  }
  return result;
}

}  // namespace

RobotJointLimits loadRobotJointLimits(const urdf::ModelInterface& model,
                                      const YAML::Node& robot_ns_node,
                                      const std::string& source_name) {
  if (source_name.empty()) return load(model, robot_ns_node);
  try {
    return load(model, robot_ns_node);
  } catch (const ConfigError& e) {
    throw ConfigError(source_name + ": " + e.what());
  }
}

}  // namespace servoloop::hardware_interface
