#pragma once
// Reading a controller's parameters (context.params, a params::Parameters
// view) with errors in the controller's own words, and naming its topics.
// Non-real-time. Every error names the controller, the full parameter path
// and the fix.
#include <cstddef>
#include <string>
#include <vector>

#include "servoloop/controller_manager/controller_context.hpp"

namespace servoloop::controllers {

using controller_manager::ControllerContext;

// "<robot ns>/<controller>/<key>" without a leading slash, e.g.
// "one_DOF_robot/joint1_position_controller/pid", as a user finds it in the YAML.
std::string parameterPath(const ControllerContext& context, const std::string& key);

// "<robot ns>/<controller>/<leaf>", e.g. "/one_DOF_robot/joint1_position_controller/command".
std::string controllerTopic(const ControllerContext& context, const std::string& leaf);
// "<robot ns>/<leaf>", e.g. "/one_DOF_robot/joint_states".
std::string namespaceTopic(const ControllerContext& context, const std::string& leaf);

// A required string, e.g. `joint: joint1`. Throws servoloop::ConfigError when
// missing or not a string; example is shown in the message ("joint: joint1").
std::string requireString(const ControllerContext& context, const std::string& key,
                          const std::string& example);
// An optional string with a default.
std::string optionalString(const ControllerContext& context, const std::string& key,
                           const std::string& fallback);

// A required non-empty list of distinct strings, e.g. `joints: [joint1, joint2]`.
std::vector<std::string> requireStringList(const ControllerContext& context, const std::string& key,
                                           const std::string& example);

// A required finite number. Throws servoloop::ConfigError when missing or not a number.
double requireNumber(const ControllerContext& context, const std::string& key,
                     const std::string& example);
// An optional finite number with a default.
double optionalNumber(const ControllerContext& context, const std::string& key, double fallback);

// The required `publish_rate` (Hz) of a state publisher (joint states, IMU,
// force-torque): 0 is kept, as ros_controllers loads it and never publishes;
// a negative rate is refused naming the parameter, its value and the fix.
double requirePublishRate(const ControllerContext& context);

// "a, b, c": names for messages.
std::string joinNames(const std::vector<std::string>& names);

// An optional number that must be >= 0 (optionalNonNegative) or > 0
// (optionalPositive); the error names the parameter, its value and the rule.
double optionalNonNegative(const ControllerContext& context, const std::string& key, double fallback);
double optionalPositive(const ControllerContext& context, const std::string& key, double fallback);

// An optional whole number from min to max that sizes what the controller
// allocates at load (a rolling window, a history): every such parameter has an
// upper bound, so a typo cannot make the node allocate gigabytes. The error
// names the parameter, its value, the range and `fix` (e.g. "ros_controllers'
// default is 10").
std::size_t optionalCount(const ControllerContext& context, const std::string& key, std::size_t fallback,
                          std::size_t min, std::size_t max, const std::string& fix);

// An optional true/false with a default.
bool optionalBool(const ControllerContext& context, const std::string& key, bool fallback);

// The number at value (or fallback when it is missing or null); where names
// it in errors.
double numberAt(const params::Parameters& value, const std::string& where, double fallback);

}  // namespace servoloop::controllers
