#pragma once
// The functions xacro's expressions may call: Python's builtins xacro exposes
// (str, int, float, len, min, max, abs, round, ...), the math module (bare or
// as math.*), and xacro.* (load_yaml, message, warning, error, fatal).
// Internal to the xacro expander.
#include <initializer_list>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "xacro_expression.hpp"
#include "xacro_value.hpp"

namespace servoloop::xacro {

// The arguments of one call: f(1, 'a', key=2).
struct Arguments {
  std::vector<Value> positional;
  std::vector<std::pair<std::string, Value>> keyword;
};

// The call's arguments matched to `parameters` as Python matches them
// (positional first, then by name); the first `required` must be given, the
// rest are nullopt when not. Throws ExpressionError naming `function` for too
// many, missing, repeated or unknown arguments.
std::vector<std::optional<Value>> bindArguments(const std::string& function, const Arguments& args,
                                                std::initializer_list<const char*> parameters,
                                                std::size_t required);

// name(args) for a function name as written: "len", "math.sqrt", "xacro.load_yaml".
Value callFunction(const std::string& name, const Arguments& args, Names& names);

}  // namespace servoloop::xacro
