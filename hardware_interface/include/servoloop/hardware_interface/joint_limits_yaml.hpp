#pragma once
// Joint limits read from YAML, as ros_control reads them from the parameter
// server under <robot ns>/joint_limits/<joint>. Non-real-time.
//
//   joint_limits:
//     joint1:
//       has_position_limits: true      # then min_position, max_position
//       min_position: 0.0
//       max_position: 2.0
//       has_velocity_limits: true      # then max_velocity
//       max_velocity: 0.5
//       has_acceleration_limits: true  # then max_acceleration
//       max_acceleration: 4.0
//       has_effort_limits: true        # then max_effort
//       max_effort: 10.0
//       has_soft_limits: true          # then k_position, k_velocity,
//       k_position: 100.0              #      soft_lower_limit, soft_upper_limit
//       k_velocity: 20.0
//       soft_lower_limit: 0.1
//       soft_upper_limit: 1.9
//
// A group is read only where its has_… key is present: `has_velocity_limits:
// false` removes a URDF velocity limit, a missing has_velocity_limits leaves it
// (and any max_velocity next to it is ignored, with a warning). With
// `has_position_limits: false`, `angle_wraparound: true|false` may follow.
// A value missing from a group switched on is taken from what the limits held
// before (the URDF); when there is nothing to take it from, that is an error.
#include <optional>
#include <string>

#include <yaml-cpp/yaml.h>

#include "servoloop/hardware_interface/joint_limits.hpp"
#include "servoloop/hardware_interface/soft_joint_limits.hpp"

namespace servoloop::hardware_interface {

// joint_node: the value of joint_limits/<joint_name> (may be undefined).
// Returns false, leaving limits untouched, when joint_node is undefined or null.
// Throws servoloop::ConfigError naming joint_limits/<joint>/<key> and the
// expected type when a key has the wrong type, when joint_node is not a map, or
// when a group is switched on without its values.
bool getJointLimits(const YAML::Node& joint_node, const std::string& joint_name,
                    JointLimits& limits);

// Soft limits from the same node. Without has_soft_limits, soft_limits is left
// as it is (e.g. from the URDF <safety_controller>); `has_soft_limits: false`
// empties it; `has_soft_limits: true` sets it, each key overriding the value it
// held. Returns soft_limits.has_value() afterwards. Throws like getJointLimits.
bool getSoftJointLimits(const YAML::Node& joint_node, const std::string& joint_name,
                        std::optional<SoftJointLimits>& soft_limits);

}  // namespace servoloop::hardware_interface
