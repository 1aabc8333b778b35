#include "servoloop/controllers/common/controller_params.hpp"

#include <algorithm>
#include <cmath>

#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/number_text.hpp"

namespace servoloop::controllers {

namespace {

std::string trimSlashes(const std::string& text) {
  const auto first = text.find_first_not_of('/');
  if (first == std::string::npos) return {};
  const auto last = text.find_last_not_of('/');
  return text.substr(first, last - first + 1);
}

std::string missingMessage(const ControllerContext& context, const std::string& key,
                           const std::string& example) {
  return "controller '" + context.name + "': parameter '" + parameterPath(context, key) +
         "' is missing; add '" + example + "' under '" + context.name + "' in the controller YAML";
}

params::Parameters child(const ControllerContext& context, const std::string& key) {
  return context.params.child(key);
}

}  // namespace

std::string parameterPath(const ControllerContext& context, const std::string& key) {
  const std::string ns = trimSlashes(context.robot_namespace);
  return (ns.empty() ? "" : ns + "/") + context.name + "/" + key;
}

std::string controllerTopic(const ControllerContext& context, const std::string& leaf) {
  return servoloop::realtime::TopicBus::normalizeTopicName(context.robot_namespace + "/" +
                                                          context.name + "/" + leaf);
}

std::string namespaceTopic(const ControllerContext& context, const std::string& leaf) {
  return servoloop::realtime::TopicBus::normalizeTopicName(context.robot_namespace + "/" + leaf);
}

std::string requireString(const ControllerContext& context, const std::string& key,
                          const std::string& example) {
  const params::Parameters value = child(context, key);
  if (value.empty()) throw ConfigError(missingMessage(context, key, example));
  if (!value.isScalar()) {
    throw ConfigError("controller '" + context.name + "': parameter '" + parameterPath(context, key) +
                      "' must be a string, e.g. '" + example + "'");
  }
  return value.as<std::string>();
}

std::string optionalString(const ControllerContext& context, const std::string& key,
                           const std::string& fallback) {
  const params::Parameters value = child(context, key);
  if (value.empty()) return fallback;
  if (!value.isScalar()) {
    throw ConfigError("controller '" + context.name + "': parameter '" + parameterPath(context, key) +
                      "' must be a string (default '" + fallback + "')");
  }
  return value.as<std::string>();
}

std::vector<std::string> requireStringList(const ControllerContext& context, const std::string& key,
                                           const std::string& example) {
  const params::Parameters value = child(context, key);
  if (value.empty()) throw ConfigError(missingMessage(context, key, example));
  const std::string wrong_form = "controller '" + context.name + "': parameter '" +
                                 parameterPath(context, key) +
                                 "' must be a non-empty list of names, e.g. '" + example + "'";
  if (!value.isList() || value.size() == 0) throw ConfigError(wrong_form);
  std::vector<std::string> names;
  for (std::size_t i = 0; i < value.size(); ++i) {
    const params::Parameters item = value.item(i);
    if (!item.isScalar()) throw ConfigError(wrong_form);
    std::string name = item.as<std::string>();
    if (std::find(names.begin(), names.end(), name) != names.end()) {
      throw ConfigError("controller '" + context.name + "': parameter '" + parameterPath(context, key) +
                        "' lists '" + name + "' twice; list each joint once");
    }
    names.push_back(std::move(name));
  }
  return names;
}

double numberAt(const params::Parameters& value, const std::string& where, double fallback) {
  if (value.empty()) return fallback;
  double number = 0.0;
  try {
    number = value.as<double>();
  } catch (const ConfigError&) {
    throw ConfigError("parameter '" + where + "' must be a finite number, got " +
                      (value.isScalar() ? value.describe() : std::string("'a list or map'")));
  }
  return number;
}

double requireNumber(const ControllerContext& context, const std::string& key,
                     const std::string& example) {
  const params::Parameters value = child(context, key);
  if (value.empty()) throw ConfigError(missingMessage(context, key, example));
  try {
    return numberAt(value, parameterPath(context, key), 0.0);
  } catch (const ConfigError& e) {
    throw ConfigError("controller '" + context.name + "': " + e.what());
  }
}

double optionalNumber(const ControllerContext& context, const std::string& key, double fallback) {
  try {
    return numberAt(child(context, key), parameterPath(context, key), fallback);
  } catch (const ConfigError& e) {
    throw ConfigError("controller '" + context.name + "': " + e.what());
  }
}

double requirePublishRate(const ControllerContext& context) {
  const double rate = requireNumber(context, "publish_rate", "publish_rate: 50");
  if (rate < 0.0) {
    throw ConfigError("controller '" + context.name + "': parameter '" + parameterPath(context, "publish_rate") +
                      "' is " + formatDouble(rate) + "; a rate is > 0 in Hz (0: never publish), e.g. publish_rate: 50");
  }
  return rate;
}

double optionalNonNegative(const ControllerContext& context, const std::string& key, double fallback) {
  const double value = optionalNumber(context, key, fallback);
  if (value < 0.0) {
    throw ConfigError("controller '" + context.name + "': parameter '" + parameterPath(context, key) + "' is " +
                      std::to_string(value) + "; it must be >= 0");
  }
  return value;
}

double optionalPositive(const ControllerContext& context, const std::string& key, double fallback) {
  const double value = optionalNumber(context, key, fallback);
  if (!(value > 0.0)) {
    throw ConfigError("controller '" + context.name + "': parameter '" + parameterPath(context, key) + "' is " +
                      std::to_string(value) + "; it must be > 0");
  }
  return value;
}

std::size_t optionalCount(const ControllerContext& context, const std::string& key, std::size_t fallback,
                          std::size_t min, std::size_t max, const std::string& fix) {
  const params::Parameters node = child(context, key);
  if (node.empty()) return fallback;
  const double value = optionalNumber(context, key, static_cast<double>(fallback));
  if (value != std::floor(value) || value < static_cast<double>(min) || value > static_cast<double>(max)) {
    throw ConfigError("controller '" + context.name + "': parameter '" + parameterPath(context, key) + "' is " +
                      node.describe() + "; it must be a whole number from " + std::to_string(min) + " to " +
                      std::to_string(max) + " (the limit; it sizes what the controller allocates at load): " + fix);
  }
  return static_cast<std::size_t>(value);
}

bool optionalBool(const ControllerContext& context, const std::string& key, bool fallback) {
  const params::Parameters value = context.params.child(key);
  if (value.empty()) return fallback;
  try {
    return value.as<bool>();
  } catch (const ConfigError&) {
    throw ConfigError("controller '" + context.name + "': parameter '" + parameterPath(context, key) +
                      "' must be true or false, got " + value.describe());
  }
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

}  // namespace servoloop::controllers
