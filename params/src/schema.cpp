#include "servoloop/params/schema.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::params {
namespace {

std::string formatNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// Levenshtein distance, for the closest known key.
std::size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// "from 1e-06 to 1", "> 0", ">= 0", "<= 99" or "" (no limits).
std::string rangeText(const KeyLimits& limits) {
  const bool has_min = std::isfinite(limits.min);
  const bool has_max = std::isfinite(limits.max);
  if (has_min && has_max && !limits.min_exclusive) {
    return "from " + formatNumber(limits.min) + " to " + formatNumber(limits.max);
  }
  std::string text;
  if (has_min) text = std::string(limits.min_exclusive ? "> " : ">= ") + formatNumber(limits.min);
  if (has_max) text += (text.empty() ? "<= " : " and <= ") + formatNumber(limits.max);
  return text;
}

// "<path>: expected <what>, got <value> (<what the key means>)".
[[noreturn]] void wrongValue(const Parameters& value, const std::string& expected, std::string_view description) {
  std::string message = value.path() + ": expected " + expected + ", got " + value.describe();
  if (!description.empty()) message.append(" (").append(description).append(")");
  throw ConfigError(message);
}

template <class T>
T readAs(const Parameters& value, const char* expected, std::string_view description) {
  if (!value.isScalar()) wrongValue(value, expected, description);
  try {
    return value.as<T>();
  } catch (const ConfigError&) {
    wrongValue(value, expected, description);
  }
}

}  // namespace

const char* toString(ValueType type) noexcept {
  switch (type) {
    case ValueType::number: return "a number";
    case ValueType::integer: return "a whole number";
    case ValueType::boolean: return "a boolean (true or false)";
    case ValueType::text: return "a text";
    case ValueType::text_list: return "a list of names";
    case ValueType::number_list: return "a list of numbers";
    case ValueType::map: return "a map";
    case ValueType::any: return "anything";
  }
  return "anything";
}

Schema::Schema(std::string subject, std::vector<Key> keys, UnknownKeys unknown)
    : subject_(std::move(subject)), keys_(std::move(keys)), unknown_(unknown) {}

const Key* Schema::find(std::string_view name) const noexcept {
  for (const Key& key : keys_) {
    if (key.name == name) return &key;
  }
  return nullptr;
}

const Key& Schema::declared(std::string_view name) const {
  const Key* key = find(name);
  // A reader asking for a key it did not declare is a programming error.
  if (key == nullptr) throw Error(subject_ + ": key '" + std::string(name) + "' is not declared");
  return *key;
}

std::string Schema::keyNames() const {
  std::string names;
  for (const Key& key : keys_) names.append(names.empty() ? "" : ", ").append(key.name);
  return names;
}

std::string_view Schema::closest(std::string_view name) const {
  std::string_view best;
  std::size_t best_distance = std::string_view::npos;
  for (const Key& key : keys_) {
    const std::size_t distance = editDistance(name, key.name);
    if (distance < best_distance) {
      best = key.name;
      best_distance = distance;
    }
  }
  // Only a near miss is a suggestion: at most a third of the name changed.
  return best_distance <= std::max<std::size_t>(1, name.size() / 3) ? best : std::string_view();
}

std::string Schema::describe() const {
  std::string text;
  for (const Key& key : keys_) {
    text.append(key.name).append(": ").append(toString(key.type));
    const std::string range = rangeText(key.limits);
    if (!range.empty()) text.append(" ").append(range);
    if (key.limits.required) {
      text.append(", required");
    } else if (key.type == ValueType::number || key.type == ValueType::integer) {
      text.append(", default ").append(formatNumber(key.limits.default_number));
    } else if (key.type == ValueType::boolean) {
      text.append(", default ").append(key.limits.default_boolean ? "true" : "false");
    } else if (key.type == ValueType::text && !key.limits.default_text.empty()) {
      text.append(", default ").append(key.limits.default_text);
    }
    text.append(" — ").append(key.description).append("\n");
  }
  return text;
}

void Schema::checkValue(const Key& key, const Parameters& value) const {
  const std::string_view about = key.description;
  switch (key.type) {
    case ValueType::number:
    case ValueType::integer: {
      const double number = key.type == ValueType::number ? readAs<double>(value, "a number", about)
                                                          : readAs<int>(value, "a whole number", about);
      const KeyLimits& limits = key.limits;
      const bool below = limits.min_exclusive ? !(number > limits.min) : !(number >= limits.min);
      if (below || !(number <= limits.max)) {
        wrongValue(value, std::string(toString(key.type)) + " " + rangeText(limits), about);
      }
      return;
    }
    case ValueType::boolean: readAs<bool>(value, toString(key.type), about); return;
    case ValueType::text: readAs<std::string>(value, toString(key.type), about); return;
    case ValueType::text_list:
    case ValueType::number_list: {
      if (!value.isList()) wrongValue(value, toString(key.type), about);
      for (std::size_t i = 0; i < value.size(); ++i) {
        if (key.type == ValueType::number_list) {
          readAs<double>(value.item(i), "a number", about);
        } else {
          readAs<std::string>(value.item(i), "a name", about);
        }
      }
      return;
    }
    case ValueType::map:
      if (!value.isMap()) wrongValue(value, toString(key.type), about);
      return;
    case ValueType::any: return;
  }
}

std::vector<std::string> Schema::check(const Parameters& node) const {
  std::vector<std::string> unknown;
  if (node.empty()) {
    for (const Key& key : keys_) {
      if (key.limits.required) throw ConfigError(node.pathOf(key.name) + ": missing (" + std::string(key.description) + ")");
    }
    return unknown;
  }
  if (!node.isMap()) {
    throw ConfigError(node.path() + ": expected a map of " + subject_ + " (" + keyNames() + "), got " +
                      node.describe());
  }
  for (const std::string& name : node.keys()) {
    const Key* key = find(name);
    if (key != nullptr) {
      const Parameters value = node.child(name);
      if (!value.empty()) checkValue(*key, value);
      continue;
    }
    unknown.push_back(name);
    if (unknown_ == UnknownKeys::allow) continue;
    const std::string_view suggestion = closest(name);
    std::string message = node.path() + ": unknown key '" + name + "'";
    if (unknown_ == UnknownKeys::warn) message += " is ignored";
    if (!suggestion.empty()) message += "; did you mean '" + std::string(suggestion) + "'?";
    message += " (the " + subject_ + " are: " + keyNames() + ")";
    if (unknown_ == UnknownKeys::error) throw ConfigError(message);
    logger().warn("{}", message);
  }
  for (const Key& key : keys_) {
    if (key.limits.required && !node.has(key.name)) {
      throw ConfigError(node.pathOf(key.name) + ": missing (" + std::string(key.description) + ")");
    }
  }
  return unknown;
}

double Schema::number(const Parameters& node, std::string_view name) const {
  const Key& key = declared(name);
  const Parameters value = node.child(name);
  if (value.empty()) {
    if (key.limits.required) throw ConfigError(value.path() + ": missing (" + std::string(key.description) + ")");
    return key.limits.default_number;
  }
  checkValue(key, value);
  return key.type == ValueType::integer ? value.as<int>() : value.as<double>();
}

int Schema::integer(const Parameters& node, std::string_view name) const {
  return static_cast<int>(number(node, name));
}

bool Schema::boolean(const Parameters& node, std::string_view name) const {
  const Key& key = declared(name);
  const Parameters value = node.child(name);
  if (value.empty()) {
    if (key.limits.required) throw ConfigError(value.path() + ": missing (" + std::string(key.description) + ")");
    return key.limits.default_boolean;
  }
  return value.as<bool>();
}

std::string Schema::text(const Parameters& node, std::string_view name) const {
  const Key& key = declared(name);
  const Parameters value = node.child(name);
  if (value.empty()) {
    if (key.limits.required) throw ConfigError(value.path() + ": missing (" + std::string(key.description) + ")");
    return std::string(key.limits.default_text);
  }
  return value.as<std::string>();
}

std::vector<std::string> Schema::textList(const Parameters& node, std::string_view name) const {
  const Key& key = declared(name);
  const Parameters value = node.child(name);
  if (value.empty()) {
    if (key.limits.required) throw ConfigError(value.path() + ": missing (" + std::string(key.description) + ")");
    return {};
  }
  return value.as<std::vector<std::string>>();
}

}  // namespace servoloop::params
