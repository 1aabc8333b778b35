#pragma once
// The values xacro expressions compute with, with Python's meaning (xacro
// evaluates `${}` as Python): None, bool, int, float, str, list and dict (the
// last two come from load_yaml and literals). Internal to the xacro expander.
#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace servoloop::xacro {

// Lists and dicts nest at most this deep. str(), repr(), ==, < and the
// destructor walk a value recursively, and a value can be built up one
// property at a time (p1 = [p0], p2 = [p1], ...) to any depth the stack would
// not survive. No robot's YAML or expression comes near it.
inline constexpr int kMaxValueDepth = 100;
// A list or dict's text (the bound below, every shared part counted each time
// it appears) is at most this long: [p, p] doubles a value, so thirty
// properties would otherwise stand for gigabytes (the billion laughs of YAML).
// As every value counts at least kScalarTextBound, it bounds the number of
// values in it too (to about 650,000).
inline constexpr std::size_t kMaxValueText = std::size_t{16} << 20;
// The longest string an operation makes (str + str, str * int, and the
// methods that multiply text: replace, join, format with widths): as long as a
// description could sensibly hold. Without it p1 = p0 + p0, p2 = p1 + p1, ...
// would stand for gigabytes.
inline constexpr std::size_t kMaxStringBytes = std::size_t{1} << 20;

struct Value {
  enum class Kind { None, Bool, Int, Float, String, List, Dict };
  // A dict's items in insertion order, as Python keeps them (keys() and str()
  // show that order). Keys are text: YAML and xacro's dicts are keyed by names.
  using DictItems = std::vector<std::pair<std::string, Value>>;
  // The longest repr of None, a bool, an int or a float ("-2.2250738585072014e-308").
  static constexpr std::size_t kScalarTextBound = 24;
  Kind kind = Kind::None;
  bool boolean = false;
  long long integer = 0;
  double real = 0.0;
  std::string text;
  std::shared_ptr<const std::vector<Value>> list;
  std::shared_ptr<const DictItems> dict;
  // How deep lists and dicts nest in the value (0 for a scalar), and a bound
  // of the length of its repr, which str() of it cannot pass (at least
  // kScalarTextBound, whatever the value). ofList and ofDict refuse
  // (ExpressionError) a value past kMaxValueDepth or kMaxValueText.
  int depth = 0;
  std::size_t text_bound = kScalarTextBound;

  static Value none() { return {}; }
  static Value ofBool(bool b);
  static Value ofInt(long long i);
  static Value ofFloat(double f);
  static Value ofString(std::string s);
  static Value ofList(std::vector<Value> items);
  // A key given twice keeps its first place and its last value, as in Python.
  static Value ofDict(DictItems items);

  bool isNumber() const { return kind == Kind::Bool || kind == Kind::Int || kind == Kind::Float; }
  // The item of a dict under `key`, or nullptr.
  const Value* find(const std::string& key) const;
};

// Python's str(): 0.5 → "0.5", 2.0 → "2.0", 1e-05 → "1e-05", True → "True".
std::string str(const Value& v);
// Python's repr(): strings quoted (used inside lists).
std::string repr(const Value& v);
// Python's name of the value's type, for error messages.
std::string typeName(const Value& v);
// The type with its article, for error messages: "an int", "a str", "None".
std::string aTypeName(const Value& v);
// The number a bool, int or float stands for.
double asDouble(const Value& v);
// Python's truth value.
bool truthy(const Value& v);
// xacro's reading of a property's text: '…' quoted text loses its quotes;
// otherwise an int, a float, or true/false/True/False become that value; text
// with an underscore and everything else stays text.
Value literal(const std::string& text);

}  // namespace servoloop::xacro
