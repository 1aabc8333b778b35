#pragma once
// The values xacro expressions compute with, with Python's meaning (xacro
// evaluates `${}` as Python): None, bool, int, float, str, list and dict (the
// last two come from load_yaml and literals). Internal to the xacro expander.
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace servoloop::xacro {

struct Value {
  enum class Kind { None, Bool, Int, Float, String, List, Dict };
  Kind kind = Kind::None;
  bool boolean = false;
  long long integer = 0;
  double real = 0.0;
  std::string text;
  std::shared_ptr<const std::vector<Value>> list;
  std::shared_ptr<const std::map<std::string, Value>> dict;

  static Value none() { return {}; }
  static Value ofBool(bool b);
  static Value ofInt(long long i);
  static Value ofFloat(double f);
  static Value ofString(std::string s);
  static Value ofList(std::vector<Value> items);
  static Value ofDict(std::map<std::string, Value> items);

  bool isNumber() const { return kind == Kind::Bool || kind == Kind::Int || kind == Kind::Float; }
};

// Python's str(): 0.5 → "0.5", 2.0 → "2.0", 1e-05 → "1e-05", True → "True".
std::string str(const Value& v);
// Python's repr(): strings quoted (used inside lists).
std::string repr(const Value& v);
// Python's name of the value's type, for error messages.
std::string typeName(const Value& v);
// The number a bool, int or float stands for.
double asDouble(const Value& v);
// Python's truth value.
bool truthy(const Value& v);
// xacro's reading of a property's text: '…' quoted text loses its quotes;
// otherwise an int, a float, or true/false/True/False become that value; text
// with an underscore and everything else stays text.
Value literal(const std::string& text);

}  // namespace servoloop::xacro
