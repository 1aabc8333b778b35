#pragma once
// Python's operators on xacro's values: arithmetic, equality and ordering,
// shared by the expression parser and the builtin functions. Internal to the
// xacro expander.
#include <cstddef>
#include <optional>
#include <string>

#include "xacro_expression.hpp"
#include "xacro_value.hpp"

namespace servoloop::xacro {

// Throws ExpressionError(message).
[[noreturn]] void fail(const std::string& message);

// Python's numeric tower: bool and int are integers, anything with a float is a float.
bool isIntegral(const Value& v);
long long toInt(const Value& v);

// a <op> b for + - * / // % ** with Python's meaning (str + str, list + list,
// str * int included).
Value binaryOp(const std::string& op, const Value& a, const Value& b);

// a == b as Python: 1 == 1.0 == True, lists item by item, dicts key by key.
bool equal(const Value& a, const Value& b);

// a <op> b for == != < <= > >= in, not in.
bool compare(const std::string& op, const Value& a, const Value& b);

// Python's slice bounds over a sequence of `length` items: negative bounds
// count from the end, bounds past either end are clamped, a missing bound is
// the start or end the step walks from. `step` is not 0.
struct SliceBounds {
  long long start = 0;
  long long count = 0;  // how many positions start, start + step, ... there are
  long long step = 1;
};
SliceBounds sliceBounds(long long length, std::optional<long long> start, std::optional<long long> stop,
                        long long step);

}  // namespace servoloop::xacro
