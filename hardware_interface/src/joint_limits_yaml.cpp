#include "servoloop/hardware_interface/joint_limits_yaml.hpp"

#include <array>
#include <string_view>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::hardware_interface {
namespace {

std::string keyPath(const std::string& joint_name, std::string_view key) {
  std::string path = "joint_limits/" + joint_name;
  if (!key.empty()) path.append("/").append(key);
  return path;
}

template <class T>
constexpr const char* expectedTypeName() {
  if constexpr (std::is_same_v<T, bool>) return "a boolean (true or false)";
  else return "a number";
}

std::string describe(const YAML::Node& value) {
  if (value.IsScalar()) return "'" + value.Scalar() + "'";
  if (value.IsSequence()) return "a list";
  if (value.IsMap()) return "a map";
  return "nothing";
}

// Reads joint_node[key] into out. Returns false when the key is absent.
template <class T>
bool readKey(const YAML::Node& joint_node, const std::string& joint_name, const char* key, T& out) {
  const YAML::Node value = joint_node[key];
  if (!value.IsDefined()) return false;
  const auto fail = [&]() {
    return ConfigError(keyPath(joint_name, key) + ": expected " + expectedTypeName<T>() + ", got " +
                       describe(value));
  };
  if (!value.IsScalar()) throw fail();
  try {
    out = value.as<T>();
  } catch (const YAML::BadConversion&) {
    throw fail();
  }
  return true;
}

// One value of a group that has_<group> switched on: the YAML value when given,
// else the previous one when the group was already set (from the URDF).
void readGroupValue(const YAML::Node& joint_node, const std::string& joint_name, const char* flag_key,
                    const char* value_key, bool previously_set, double& value) {
  if (readKey(joint_node, joint_name, value_key, value) || previously_set) return;
  throw ConfigError(keyPath(joint_name, "") + ": " + flag_key + " is true but " + value_key +
                    " is missing; add " + value_key + " or set " + flag_key + ": false");
}

// Keys that belong to a group are ignored when the group's has_… key is absent;
// say so, since it is almost always a forgotten has_… line.
void warnIgnoredKey(const YAML::Node& joint_node, const std::string& joint_name, const char* flag_key,
                    const char* value_key) {
  if (joint_node[value_key].IsDefined() && !joint_node[flag_key].IsDefined()) {
    logger().warn("{}: {} is ignored because {} is not set", keyPath(joint_name, ""), value_key,
                  flag_key);
  }
}

constexpr std::array<std::string_view, 15> kKnownKeys = {
    "has_position_limits", "min_position",     "max_position",     "angle_wraparound",
    "has_velocity_limits", "max_velocity",     "has_acceleration_limits",
    "max_acceleration",    "has_effort_limits", "max_effort",       "has_soft_limits",
    "k_position",          "k_velocity",       "soft_lower_limit", "soft_upper_limit"};

void requireMap(const YAML::Node& joint_node, const std::string& joint_name) {
  if (!joint_node.IsMap()) {
    throw ConfigError(keyPath(joint_name, "") + ": expected a map of limit keys (has_position_limits, " +
                      "min_position, ...), got " + describe(joint_node));
  }
}

}  // namespace

bool getJointLimits(const YAML::Node& joint_node, const std::string& joint_name,
                    JointLimits& limits) {
  if (!joint_node.IsDefined() || joint_node.IsNull()) return false;
  requireMap(joint_node, joint_name);

  for (const auto& entry : joint_node) {
    const std::string key = entry.first.as<std::string>();
    bool known = false;
    for (std::string_view k : kKnownKeys) known = known || k == key;
    if (!known) logger().warn("{}: unknown key '{}' is ignored", keyPath(joint_name, ""), key);
  }

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

bool getSoftJointLimits(const YAML::Node& joint_node, const std::string& joint_name,
                        std::optional<SoftJointLimits>& soft_limits) {
  if (!joint_node.IsDefined() || joint_node.IsNull()) return soft_limits.has_value();
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
  readGroupValue(joint_node, joint_name, "has_soft_limits", "soft_lower_limit", previously_set,
                 result.min_position);
  readGroupValue(joint_node, joint_name, "has_soft_limits", "soft_upper_limit", previously_set,
                 result.max_position);
  soft_limits = result;
  return true;
}

}  // namespace servoloop::hardware_interface
