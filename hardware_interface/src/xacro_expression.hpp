#pragma once
// The expressions inside xacro's `${...}`: the part of Python real robot
// descriptions use. Literals (numbers, 'strings', True/False/None, [lists]),
// names (properties, dotted `ns.name` and `dict.key`), arithmetic
// (+ - * / // % **), comparisons (chained), not/and/or, `x if c else y`, `in`,
// indexing, and the math module and builtins xacro offers (pi, e, radians,
// degrees, sin, cos, tan, asin, acos, atan, atan2, sqrt, exp, log, log10, pow,
// fabs, floor, ceil, abs, min, max, round, int, float, bool, str, len, sum,
// load_yaml). Internal to the xacro expander.
#include <optional>
#include <stdexcept>
#include <string>

#include "xacro_value.hpp"

namespace servoloop::xacro {

// What an expression cannot work out by itself.
class Names {
 public:
  virtual ~Names() = default;
  // The value of property `name` (possibly dotted), or nullopt if undefined.
  virtual std::optional<Value> lookup(const std::string& name) = 0;
  // xacro.load_yaml(file): the YAML file's content as values.
  virtual Value loadYaml(const std::string& file) = 0;
};

// An expression that cannot be evaluated; the message says why (the caller
// adds the file, line and expression).
class ExpressionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

Value evaluate(const std::string& expression, Names& names);

}  // namespace servoloop::xacro
