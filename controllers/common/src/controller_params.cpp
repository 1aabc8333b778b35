#include "servoloop/controllers/common/controller_params.hpp"

#include <algorithm>
#include <cmath>

#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/core/errors.hpp"

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

YAML::Node child(const ControllerContext& context, const std::string& key) {
  return childNode(context.params, key);
}

}  // namespace

YAML::Node childNode(const YAML::Node& map, const std::string& key) {
  if (!map.IsDefined() || !map.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
  const YAML::Node found = map[key];  // const lookup: does not insert the key
  return found.IsDefined() ? found : YAML::Node(YAML::NodeType::Undefined);
}

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
  const YAML::Node node = child(context, key);
  if (!node.IsDefined() || node.IsNull()) throw ConfigError(missingMessage(context, key, example));
  if (!node.IsScalar()) {
    throw ConfigError("controller '" + context.name + "': parameter '" + parameterPath(context, key) +
                      "' must be a string, e.g. '" + example + "'");
  }
  return node.as<std::string>();
}

std::string optionalString(const ControllerContext& context, const std::string& key,
                           const std::string& fallback) {
  const YAML::Node node = child(context, key);
  if (!node.IsDefined() || node.IsNull()) return fallback;
  if (!node.IsScalar()) {
    throw ConfigError("controller '" + context.name + "': parameter '" + parameterPath(context, key) +
                      "' must be a string (default '" + fallback + "')");
  }
  return node.as<std::string>();
}

std::vector<std::string> requireStringList(const ControllerContext& context, const std::string& key,
                                           const std::string& example) {
  const YAML::Node node = child(context, key);
  if (!node.IsDefined() || node.IsNull()) throw ConfigError(missingMessage(context, key, example));
  const std::string wrong_form = "controller '" + context.name + "': parameter '" +
                                 parameterPath(context, key) +
                                 "' must be a non-empty list of names, e.g. '" + example + "'";
  if (!node.IsSequence() || node.size() == 0) throw ConfigError(wrong_form);
  std::vector<std::string> names;
  for (const YAML::Node& item : node) {
    if (!item.IsScalar()) throw ConfigError(wrong_form);
    std::string name = item.as<std::string>();
    if (std::find(names.begin(), names.end(), name) != names.end()) {
      throw ConfigError("controller '" + context.name + "': parameter '" + parameterPath(context, key) +
                        "' lists '" + name + "' twice; list each joint once");
    }
    names.push_back(std::move(name));
  }
  return names;
}

double numberAt(const YAML::Node& node, const std::string& where, double fallback) {
  if (!node.IsDefined() || node.IsNull()) return fallback;
  double value = 0.0;
  bool ok = node.IsScalar();
  if (ok) {
    try {
      value = node.as<double>();
    } catch (const YAML::Exception&) {
      ok = false;
    }
  }
  if (!ok || !std::isfinite(value)) {
    throw ConfigError("parameter '" + where + "' must be a finite number, got '" +
                      (node.IsScalar() ? node.Scalar() : std::string("a list or map")) + "'");
  }
  return value;
}

double requireNumber(const ControllerContext& context, const std::string& key,
                     const std::string& example) {
  const YAML::Node node = child(context, key);
  if (!node.IsDefined() || node.IsNull()) throw ConfigError(missingMessage(context, key, example));
  try {
    return numberAt(node, parameterPath(context, key), 0.0);
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

}  // namespace servoloop::controllers
