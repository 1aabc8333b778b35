#include "servoloop/hardware_interface/joint_limits_yaml.hpp"

#include <array>
#include <cmath>
#include <utility>
#include <string_view>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/core/number_text.hpp"
#include "servoloop/params/parameters_yaml.hpp"
#include "servoloop/params/schema.hpp"

namespace servoloop::hardware_interface {
namespace {

std::string keyPath(const std::string& joint_name, std::string_view key) {
  std::string path = "joint_limits/" + joint_name;
  if (!key.empty()) path.append("/").append(key);
  return path;
}

// Reads joint_node[key] into out. Returns false when the key is absent.
template <class T>
bool readKey(const params::Parameters& joint_node, const std::string& joint_name, const char* key, T& out) {
  return params::readOptional(joint_node, key, keyPath(joint_name, ""), out);
}

// One value of a group that has_<group> switched on: the YAML value when given,
// else the previous one when the group was already set (from the URDF).
void readGroupValue(const params::Parameters& joint_node, const std::string& joint_name, const char* flag_key,
                    const char* value_key, bool previously_set, double& value) {
  if (readKey(joint_node, joint_name, value_key, value) || previously_set) return;
  throw ConfigError(keyPath(joint_name, "") + ": " + flag_key + " is true but " + value_key +
                    " is missing; add " + value_key + " or set " + flag_key + ": false");
}

// Keys that belong to a group are ignored when the group's has_… key is absent;
// say so, since it is almost always a forgotten has_… line.
void warnIgnoredKey(const params::Parameters& joint_node, const std::string& joint_name, const char* flag_key,
                    const char* value_key) {
  if (joint_node.has(value_key) && !joint_node.has(flag_key)) {
    logger().warn("{}: {} is ignored because {} is not set", keyPath(joint_name, ""), value_key,
                  flag_key);
  }
}

// The keys of joint_limits_interface's YAML (joint_limits_rosparam.h), one
// joint's map. Groups: a value is read only when its has_… key is true.
const params::Schema& jointLimitsSchema() {
  using params::ValueType;
  static const params::Schema schema(
      "joint limits",
      {
          {"has_position_limits", ValueType::boolean, "min_position and max_position apply"},
          {"min_position", ValueType::number, "lowest position (rad or m)"},
          {"max_position", ValueType::number, "highest position (rad or m)"},
          {"angle_wraparound", ValueType::boolean, "a continuous joint (read when has_position_limits is false)"},
          {"has_velocity_limits", ValueType::boolean, "max_velocity applies"},
          {"max_velocity", ValueType::number, "largest speed (rad/s or m/s)"},
          {"has_acceleration_limits", ValueType::boolean, "max_acceleration applies"},
          {"max_acceleration", ValueType::number, "largest acceleration (rad/s² or m/s²)"},
          {"has_effort_limits", ValueType::boolean, "max_effort applies"},
          {"max_effort", ValueType::number, "largest effort (N·m or N)"},
          {"has_soft_limits", ValueType::boolean, "the soft limits below apply"},
          {"k_position", ValueType::number, "soft limits' position gain (1/s)"},
          {"k_velocity", ValueType::number, "soft limits' velocity gain"},
          {"soft_lower_limit", ValueType::number, "soft lower position limit"},
          {"soft_upper_limit", ValueType::number, "soft upper position limit"},
      },
      params::UnknownKeys::warn);
  return schema;
}

void requireMap(const params::Parameters& joint_node, const std::string& joint_name) {
  if (!joint_node.isMap()) {
    throw ConfigError(keyPath(joint_name, "") + ": expected a map of limit keys (has_position_limits, " +
                      "min_position, ...), got " + joint_node.describe());
  }
}

}  // namespace

bool getJointLimits(const YAML::Node& yaml, const std::string& joint_name, JointLimits& limits) {
  const params::Parameters joint_node = params::parametersFromYaml(yaml, "/joint_limits/" + joint_name);
  if (joint_node.empty()) return false;
  requireMap(joint_node, joint_name);

  // Unknown keys (one warning each: ros_control ignores them without a word)
  // and the values' types.
  jointLimitsSchema().check(joint_node);

  // Read into a copy so a bad key leaves the caller's limits as they were.
  JointLimits result = limits;
  bool flag = false;

  if (readKey(joint_node, joint_name, "has_position_limits", flag)) {
    if (flag) {
      readGroupValue(joint_node, joint_name, "has_position_limits", "min_position",
                     limits.has_position_limits, result.min_position);
      readGroupValue(joint_node, joint_name, "has_position_limits", "max_position",
                     limits.has_position_limits, result.max_position);
      result.has_position_limits = true;
      result.angle_wraparound = false;
    } else {
      result.has_position_limits = false;
      readKey(joint_node, joint_name, "angle_wraparound", result.angle_wraparound);
    }
  } else {
    warnIgnoredKey(joint_node, joint_name, "has_position_limits", "min_position");
    warnIgnoredKey(joint_node, joint_name, "has_position_limits", "max_position");
  }

  struct MagnitudeGroup {
    const char* flag_key;
    const char* value_key;
    bool JointLimits::*has;
    double JointLimits::*value;
  };
  constexpr std::array<MagnitudeGroup, 3> groups = {{
      {"has_velocity_limits", "max_velocity", &JointLimits::has_velocity_limits,
       &JointLimits::max_velocity},
      {"has_acceleration_limits", "max_acceleration", &JointLimits::has_acceleration_limits,
       &JointLimits::max_acceleration},
      {"has_effort_limits", "max_effort", &JointLimits::has_effort_limits, &JointLimits::max_effort},
  }};
  for (const MagnitudeGroup& group : groups) {
    if (readKey(joint_node, joint_name, group.flag_key, flag)) {
      if (flag) {
        readGroupValue(joint_node, joint_name, group.flag_key, group.value_key, limits.*group.has,
                       result.*group.value);
      }
      result.*group.has = flag;
    } else {
      warnIgnoredKey(joint_node, joint_name, group.flag_key, group.value_key);
    }
  }

  limits = result;
  return true;
}

bool getSoftJointLimits(const YAML::Node& yaml, const std::string& joint_name,
                        std::optional<SoftJointLimits>& soft_limits) {
  const params::Parameters joint_node = params::parametersFromYaml(yaml, "/joint_limits/" + joint_name);
  if (joint_node.empty()) return soft_limits.has_value();
  requireMap(joint_node, joint_name);

  bool has_soft_limits = false;
  if (!readKey(joint_node, joint_name, "has_soft_limits", has_soft_limits)) {
    for (const char* key : {"k_position", "k_velocity", "soft_lower_limit", "soft_upper_limit"}) {
      warnIgnoredKey(joint_node, joint_name, "has_soft_limits", key);
    }
    return soft_limits.has_value();
  }
  if (!has_soft_limits) {
    soft_limits.reset();
    return false;
  }

  const bool previously_set = soft_limits.has_value();
  SoftJointLimits result = soft_limits.value_or(SoftJointLimits{});
  readGroupValue(joint_node, joint_name, "has_soft_limits", "k_position", previously_set,
                 result.k_position);
  readGroupValue(joint_node, joint_name, "has_soft_limits", "k_velocity", previously_set,
                 result.k_velocity);
  // ros_control's soft limits push back with -k·(distance past the limit): a
  // negative (or infinite) gain would drive the joint further out instead.
  for (const auto& [key, gain] : {std::pair{"k_position", result.k_position}, std::pair{"k_velocity", result.k_velocity}}) {
    if (!(std::isfinite(gain) && gain >= 0.0)) {
      throw ConfigError(keyPath(joint_name, key) + ": " + formatDouble(gain) +
                        " is not a gain soft limits can use; a negative or non-finite gain drives the joint past "
                        "its limit instead of back: give a finite gain >= 0 (e.g. " + key + ": 10)");
    }
  }
  readGroupValue(joint_node, joint_name, "has_soft_limits", "soft_lower_limit", previously_set,
                 result.min_position);
  readGroupValue(joint_node, joint_name, "has_soft_limits", "soft_upper_limit", previously_set,
                 result.max_position);
  soft_limits = result;
  return true;
}

}  // namespace servoloop::hardware_interface
