#include "my_backends/first_order_robot_hw.hpp"

#include <cmath>
#include <memory>
#include <sstream>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"

namespace my_backends {

namespace {

// A positive finite number at robot_ns/first_order/<key>, or `fallback` when the key is absent.
double positiveNumber(const YAML::Node& section, const std::string& key, const std::string& section_name,
                      double fallback, const char* unit) {
  const YAML::Node value = section[key];
  if (!value) return fallback;
  double number = 0.0;
  bool ok = value.IsScalar();
  if (ok) {
    try {
      number = value.as<double>();
    } catch (const YAML::Exception&) {
      ok = false;
    }
  }
  if (!ok || !std::isfinite(number) || number <= 0.0) {
    std::ostringstream message;
    message << section_name << "/" << key << ": expected a positive number (" << unit << "), got '" << value
            << "'; e.g. '" << key << ": " << fallback << "'";
    throw servoloop::ConfigError(message.str());
  }
  return number;
}

}  // namespace

FirstOrderParameters parseFirstOrderParameters(const YAML::Node& robot_ns, const std::string& ns) {
  FirstOrderParameters parameters;
  const std::string section_name = ns + "/first_order";
  if (!robot_ns || !robot_ns.IsMap() || !robot_ns["first_order"]) return parameters;
  const YAML::Node section = robot_ns["first_order"];
  if (!section.IsMap()) {
    throw servoloop::ConfigError(section_name +
                                 ": expected a map with time_constant and damping, e.g. "
                                 "'first_order: {time_constant: 0.05, damping: 1.0}'");
  }
  parameters.time_constant_s =
      positiveNumber(section, "time_constant", section_name, parameters.time_constant_s, "s");
  parameters.damping = positiveNumber(section, "damping", section_name, parameters.damping, "N·m·s/rad");
  for (const auto& entry : section) {
    const std::string key = entry.first.as<std::string>();
    if (key != "time_constant" && key != "damping") {
      servoloop::logger().warn("{}/{}: unknown key, ignored (the keys here are: time_constant, damping)",
                               section_name, key);
    }
  }
  return parameters;
}

FirstOrderRobotHW::FirstOrderRobotHW() : FirstOrderRobotHW(new FirstOrderPhysics) {}

FirstOrderRobotHW::FirstOrderRobotHW(FirstOrderPhysics* physics)
    : SimRobotHW(std::unique_ptr<servoloop::sim_common::PhysicsEngine>(physics)), physics_(physics) {}

void FirstOrderRobotHW::init(const servoloop::hardware_interface::HardwareInfo& info) {
  physics_->configure(parseFirstOrderParameters(info.parameters, info.robot_namespace));
  SimRobotHW::init(info);
}

}  // namespace my_backends
