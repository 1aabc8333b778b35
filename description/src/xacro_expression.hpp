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

// A limit of xacro's nesting was passed. The message is whole (it names what
// nests, the limit and the fix), so callers that add context to an
// ExpressionError (the property, the ${...} it sits in) pass this one on as it is:
// it may come from hundreds of levels down.
class LimitError : public ExpressionError {
 public:
  using ExpressionError::ExpressionError;
};

// Everything in xacro that recurses counts its levels together: elements
// inside elements (with macro bodies, includes and blocks), properties
// defined through properties, $(...) inside $(...), and brackets, parentheses
// and operators inside one another in expressions. Most have a limit of their
// own below this one (so their error names them: 100 levels in one
// expression, 100 properties, 20 $(...), 100 macro calls); this one holds for
// any mix of them, and for elements, which have none of their own. A level takes at most about 10 KB of stack (the largest are a macro
// call and a function's argument: frames measured in the debug build with
// AddressSanitizer), so the deepest expansion stays under 4 MB of the usual
// 8 MB, leaving room for what runs at the deepest level without counting
// (yaml-cpp parsing a file for load_yaml, str() of a value, tinyxml2).
inline constexpr int kMaxRecursion = 400;

// One level of that count, left when destroyed. Its constructor calls
// `refuse` (which must throw) instead of entering a level past kMaxRecursion.
class RecursionLevel {
 public:
  template <typename Refuse>
  explicit RecursionLevel(Refuse&& refuse) {
    if (depth() >= kMaxRecursion) refuse();
    ++depth();
  }
  ~RecursionLevel() { --depth(); }
  RecursionLevel(const RecursionLevel&) = delete;
  RecursionLevel& operator=(const RecursionLevel&) = delete;

  // The levels entered on this thread.
  static int& depth();
};

// The message for a level past kMaxRecursion: `here` says what the level was.
std::string recursionLimitText(const std::string& here);

// `text` as messages show it: up to 120 characters, a longer text cut in the
// middle (an expression may be megabytes long).
std::string shortened(const std::string& text);

Value evaluate(const std::string& expression, Names& names);

}  // namespace servoloop::xacro
