#pragma once
// The expressions inside xacro's `${...}`: the part of Python real robot
// descriptions use. Literals (numbers, 'strings', True/False/None, [lists],
// {dicts}), names (properties, `ns.name` of an include's namespace),
// arithmetic (+ - * / // % **), comparisons (chained), not/and/or,
// `x if c else y`, `in`; then, on any value, .key of a dict, method calls
// ('a b'.split(' '), '{}_link'.format(n)), indexing (v[0], v[-1], d['key'])
// and slicing (s[1:-1], v[::2]) with Python's rules; and the functions of
// xacro_builtins.hpp. Internal to the xacro expander.
#include <optional>
#include <stdexcept>
#include <string>

#include "xacro_value.hpp"

namespace servoloop::xacro {

// What an expression cannot work out by itself.
class Names {
 public:
  virtual ~Names() = default;
  // The value of property `name`, or of `ns.name` in an include's namespace,
  // or nullopt if undefined.
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
