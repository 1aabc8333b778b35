#pragma once
// Methods of xacro's values, with Python's meaning: str's split, rsplit, join,
// format, strip, lstrip, rstrip, replace, lower, upper, startswith, endswith,
// find, count; list's index and count; dict's keys, values and get.
// Internal to the xacro expander.
#include <string>

#include "xacro_builtins.hpp"
#include "xacro_value.hpp"

namespace servoloop::xacro {

// receiver.method(args); `call` is the call as written, for messages. Throws
// ExpressionError for a method the receiver's type does not have (naming the
// ones it has) and for bad arguments.
Value callMethod(const Value& receiver, const std::string& method, const Arguments& args, const std::string& call);

// True if `method` is a method of the receiver's type.
bool hasMethod(const Value& receiver, const std::string& method);

// The methods of the receiver's type, "split, rsplit, ...", or "" if none.
std::string methodNames(const Value& receiver);

}  // namespace servoloop::xacro
