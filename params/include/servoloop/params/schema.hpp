#pragma once
// Declarative parameter reading: each YAML reader of servoloop (launch files,
// simulation settings, joint limits, PID gains, the controller manager's own
// keys) declares its keys once — name, type, range, default and what the key
// means — and reads them through the schema, which gives every reader the
// same checks and the same messages:
//
//   const params::Schema kGains("PID gains", {
//       {"p", params::ValueType::number, "proportional gain", {.default_number = 0.0}},
//       {"i_clamp", params::ValueType::number, "integral clamp (both signs)", {.min = 0.0}},
//   }, params::UnknownKeys::warn);
//   kGains.check(node);                       // unknown keys, types, ranges
//   const double p = kGains.number(node, "p");  // the value, or the declared default
//
// Errors are servoloop::ConfigError naming the full parameter path, what was
// found and what is expected; an unknown key names the closest known one.
// Non-real-time.
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "servoloop/params/parameters.hpp"

namespace servoloop::params {

enum class ValueType : std::uint8_t {
  number,       // a finite number
  integer,      // a whole number
  boolean,      // true or false
  text,         // a scalar read as text
  text_list,    // a list of scalars read as text
  number_list,  // a list of finite numbers
  map,          // a map, checked by its reader
  any,          // anything, checked by its reader
};

// "a number", "a list of numbers", ...
const char* toString(ValueType type) noexcept;

// What a key may hold besides its type; the defaults allow everything.
struct KeyLimits {
  double min = -std::numeric_limits<double>::infinity();  // numbers: the smallest allowed value
  double max = std::numeric_limits<double>::infinity();   // numbers: the largest allowed value
  bool min_exclusive = false;                              // numbers: min itself is not allowed
  bool required = false;                                   // the key must be present
  double default_number = 0.0;                             // numbers: the value when the key is absent
  bool default_boolean = false;                            // booleans: the value when the key is absent
  std::string_view default_text{};                         // text: the value when the key is absent
};

struct Key {
  std::string_view name;
  ValueType type = ValueType::any;
  std::string_view description;  // what the key means, with its unit
  KeyLimits limits{};
};

// What a key the schema does not declare gets.
enum class UnknownKeys : std::uint8_t {
  error,  // a ConfigError naming the known keys (launch files: a typo must not pass)
  warn,   // one warning each, and the key is ignored (as ros_control ignores it)
  allow,  // nothing: the map holds keys of others too (a controller's own keys)
};

class Schema {
 public:
  // subject: what the keys configure, as messages say it ("PID gains").
  Schema(std::string subject, std::vector<Key> keys, UnknownKeys unknown);

  // Checks every key of node: the map itself, unknown keys (by the policy),
  // missing required keys, types and ranges. Throws ConfigError for the first
  // problem, naming node.pathOf(key); an empty node passes unless a key is
  // required. Returns the unknown keys found (warned or allowed).
  std::vector<std::string> check(const Parameters& node) const;

  // The value of a declared key, or its declared default when absent; throws
  // ConfigError as check() would for a value of the wrong type or range.
  double number(const Parameters& node, std::string_view name) const;
  int integer(const Parameters& node, std::string_view name) const;
  bool boolean(const Parameters& node, std::string_view name) const;
  std::string text(const Parameters& node, std::string_view name) const;
  std::vector<std::string> textList(const Parameters& node, std::string_view name) const;

  const std::string& subject() const noexcept { return subject_; }
  const std::vector<Key>& keys() const noexcept { return keys_; }
  // The declared key, or nullptr.
  const Key* find(std::string_view name) const noexcept;
  // "p, i, d, i_clamp".
  std::string keyNames() const;
  // The declared key whose name is closest to name (for "did you mean").
  std::string_view closest(std::string_view name) const;
  // One line per key: name, type, default or "required", range, description.
  std::string describe() const;

 private:
  const Key& declared(std::string_view name) const;
  void checkValue(const Key& key, const Parameters& value) const;

  std::string subject_;
  std::vector<Key> keys_;
  UnknownKeys unknown_;
};

}  // namespace servoloop::params
