#include "xacro_value.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <unordered_map>

#include "xacro_expression.hpp"

namespace servoloop::xacro {

Value Value::ofBool(bool b) {
  Value v;
  v.kind = Kind::Bool;
  v.boolean = b;
  return v;
}

Value Value::ofInt(long long i) {
  Value v;
  v.kind = Kind::Int;
  v.integer = i;
  return v;
}

Value Value::ofFloat(double f) {
  Value v;
  v.kind = Kind::Float;
  v.real = f;
  return v;
}

namespace {

// The repr of a str is at most its quotes and every character escaped.
std::size_t stringTextBound(const std::string& s) { return std::max(Value::kScalarTextBound, 2 + 2 * s.size()); }

// Adds one item's text bound (and its ", " separator) to a container's; stops
// adding once past the limit, so no sum can wrap around.
void addTextBound(std::size_t& bound, std::size_t item) {
  bound = item > kMaxValueText || bound > kMaxValueText ? kMaxValueText + 1 : bound + item + 2;
}

// The depth and text bound of a list or dict (raised to the least any value
// counts), refused past the limits.
void checkContainer(Value& v) {
  v.text_bound = std::max(v.text_bound, Value::kScalarTextBound);
  const char* what = v.kind == Value::Kind::List ? "a list" : "a dict";
  if (v.depth > kMaxValueDepth) {
    throw ExpressionError(std::string(what) + " nested more than " + std::to_string(kMaxValueDepth) +
                          " levels deep (lists and dicts inside each other) is refused: xacro's values nest at most " +
                          std::to_string(kMaxValueDepth) + " levels; does a property wrap another again and again "
                          "(p1 = [p0], p2 = [p1], ...)?");
  }
  if (v.text_bound > kMaxValueText) {
    throw ExpressionError(std::string(what) + " whose text would pass " + std::to_string(kMaxValueText >> 20) +
                          " MiB (every list or dict in it counted each time it appears) is refused; does a property "
                          "double another again and again (p1 = [p0, p0], p2 = p1 + p1, ...)?");
  }
}

}  // namespace

Value Value::ofString(std::string s) {
  Value v;
  v.kind = Kind::String;
  v.text = std::move(s);
  v.text_bound = stringTextBound(v.text);
  return v;
}

Value Value::ofList(std::vector<Value> items) {
  Value v;
  v.kind = Kind::List;
  v.depth = 1;
  v.text_bound = 2;  // []
  for (const Value& item : items) {
    v.depth = std::max(v.depth, item.depth + 1);
    addTextBound(v.text_bound, item.text_bound);
  }
  checkContainer(v);
  v.list = std::make_shared<const std::vector<Value>>(std::move(items));
  return v;
}

Value Value::ofDict(DictItems items) {
  DictItems unique;
  unique.reserve(items.size());
  std::unordered_map<std::string, std::size_t> place;
  for (auto& [key, item] : items) {
    const auto [it, added] = place.emplace(key, unique.size());
    if (added) {
      unique.emplace_back(std::move(key), std::move(item));
    } else {
      unique[it->second].second = std::move(item);
    }
  }
  Value v;
  v.kind = Kind::Dict;
  v.depth = 1;
  v.text_bound = 2;  // {}
  for (const auto& [key, item] : unique) {
    v.depth = std::max(v.depth, item.depth + 1);
    addTextBound(v.text_bound, stringTextBound(key) + 2 + item.text_bound);  // 'key': item
  }
  checkContainer(v);
  v.dict = std::make_shared<const DictItems>(std::move(unique));
  return v;
}

const Value* Value::find(const std::string& key) const {
  if (kind != Kind::Dict) return nullptr;
  for (const auto& [name, item] : *dict) {
    if (name == key) return &item;
  }
  return nullptr;
}

namespace {

// Python's repr of a float: the shortest text that reads back to the same
// double, positional for exponents in [-4, 16), scientific otherwise.
std::string floatText(double f) {
  if (std::isnan(f)) return "nan";
  if (std::isinf(f)) return f > 0 ? "inf" : "-inf";
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, f, std::chars_format::scientific);
  std::string sci(buffer, result.ptr);
  const auto e = sci.find('e');
  std::string mantissa = sci.substr(0, e);
  const int exponent = std::atoi(sci.c_str() + e + 1);
  const bool negative = !mantissa.empty() && mantissa[0] == '-';
  if (negative) mantissa.erase(0, 1);
  std::string digits;
  for (char c : mantissa) {
    if (c != '.') digits += c;
  }
  std::string out;
  if (exponent >= -4 && exponent < 16) {
    if (exponent < 0) {
      out = "0." + std::string(static_cast<std::size_t>(-exponent - 1), '0') + digits;
    } else if (static_cast<int>(digits.size()) <= exponent + 1) {
      out = digits + std::string(static_cast<std::size_t>(exponent + 1 - static_cast<int>(digits.size())), '0') + ".0";
    } else {
      out = digits.substr(0, static_cast<std::size_t>(exponent + 1)) + "." +
            digits.substr(static_cast<std::size_t>(exponent + 1));
    }
  } else {
    out = digits.substr(0, 1);
    if (digits.size() > 1) out += "." + digits.substr(1);
    const int magnitude = std::abs(exponent);
    out += std::string("e") + (exponent < 0 ? "-" : "+") + (magnitude < 10 ? "0" : "") + std::to_string(magnitude);
  }
  return negative ? "-" + out : out;
}

}  // namespace

std::string str(const Value& v) {
  switch (v.kind) {
    case Value::Kind::None: return "None";
    case Value::Kind::Bool: return v.boolean ? "True" : "False";
    case Value::Kind::Int: return std::to_string(v.integer);
    case Value::Kind::Float: return floatText(v.real);
    case Value::Kind::String: return v.text;
    case Value::Kind::List: {
      std::string out = "[";
      for (std::size_t i = 0; i < v.list->size(); ++i) out += (i ? ", " : "") + repr((*v.list)[i]);
      return out + "]";
    }
    case Value::Kind::Dict: {
      std::string out = "{";
      bool first = true;
      for (const auto& [key, item] : *v.dict) {
        out += (first ? "" : ", ") + repr(Value::ofString(key)) + ": " + repr(item);
        first = false;
      }
      return out + "}";
    }
  }
  return "";
}

std::string repr(const Value& v) {
  if (v.kind != Value::Kind::String) return str(v);
  // Python quotes with ' unless the text holds a ' and no ".
  const bool has_single = v.text.find('\'') != std::string::npos;
  const char quote = has_single && v.text.find('"') == std::string::npos ? '"' : '\'';
  std::string out(1, quote);
  for (const char c : v.text) {
    if (c == '\\' || c == quote) {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\r') {
      out += "\\r";
    } else {
      out += c;
    }
  }
  return out + quote;
}

std::string typeName(const Value& v) {
  switch (v.kind) {
    case Value::Kind::None: return "None";
    case Value::Kind::Bool: return "bool";
    case Value::Kind::Int: return "int";
    case Value::Kind::Float: return "float";
    case Value::Kind::String: return "str";
    case Value::Kind::List: return "list";
    case Value::Kind::Dict: return "dict";
  }
  return "?";
}

std::string aTypeName(const Value& v) {
  switch (v.kind) {
    case Value::Kind::None: return "None";
    case Value::Kind::Int: return "an int";
    default: return "a " + typeName(v);
  }
}

double asDouble(const Value& v) {
  switch (v.kind) {
    case Value::Kind::Bool: return v.boolean ? 1.0 : 0.0;
    case Value::Kind::Int: return static_cast<double>(v.integer);
    case Value::Kind::Float: return v.real;
    default: return 0.0;
  }
}

bool truthy(const Value& v) {
  switch (v.kind) {
    case Value::Kind::None: return false;
    case Value::Kind::Bool: return v.boolean;
    case Value::Kind::Int: return v.integer != 0;
    case Value::Kind::Float: return v.real != 0.0;
    case Value::Kind::String: return !v.text.empty();
    case Value::Kind::List: return !v.list->empty();
    case Value::Kind::Dict: return !v.dict->empty();
  }
  return false;
}

Value literal(const std::string& text) {
  if (text.size() >= 2 && text.front() == '\'' && text.back() == '\'') {
    return Value::ofString(text.substr(1, text.size() - 2));
  }
  if (text.find('_') != std::string::npos) return Value::ofString(text);
  const auto first = text.find_first_not_of(" \t\r\n");
  const auto last = text.find_last_not_of(" \t\r\n");
  if (first != std::string::npos) {
    std::string trimmed = text.substr(first, last - first + 1);
    if (trimmed[0] == '+') trimmed.erase(0, 1);
    long long i = 0;
    const char* begin = trimmed.data();
    const char* end = begin + trimmed.size();
    if (auto r = std::from_chars(begin, end, i); r.ec == std::errc() && r.ptr == end) return Value::ofInt(i);
    double f = 0.0;
    if (auto r = std::from_chars(begin, end, f); r.ec == std::errc() && r.ptr == end) return Value::ofFloat(f);
    if (trimmed == "inf" || trimmed == "Infinity") return Value::ofFloat(HUGE_VAL);
    if (trimmed == "-inf" || trimmed == "-Infinity") return Value::ofFloat(-HUGE_VAL);
  }
  if (text == "true" || text == "True") return Value::ofBool(true);
  if (text == "false" || text == "False") return Value::ofBool(false);
  return Value::ofString(text);
}

}  // namespace servoloop::xacro
