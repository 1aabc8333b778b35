#include "xacro_builtins.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>

#include "servoloop/core/logging.hpp"
#include "xacro_operators.hpp"

namespace servoloop::xacro {

std::vector<std::optional<Value>> bindArguments(const std::string& function, const Arguments& args,
                                                std::initializer_list<const char*> parameters,
                                                std::size_t required) {
  const std::vector<const char*> names(parameters);
  std::vector<std::optional<Value>> bound(names.size());
  if (args.positional.size() > names.size()) {
    fail(function + "() takes " + (names.size() == required ? "" : "at most ") + std::to_string(names.size()) +
         " argument(s), " + std::to_string(args.positional.size()) + " given");
  }
  for (std::size_t i = 0; i < args.positional.size(); ++i) bound[i] = args.positional[i];
  for (const auto& keyword : args.keyword) {
    // Named, not a structured binding: clang 14 cannot capture those in a lambda.
    const auto& key = keyword.first;
    const auto& value = keyword.second;
    const auto it = std::find_if(names.begin(), names.end(), [&](const char* n) { return key == n; });
    if (it == names.end()) {
      std::string known;
      for (const char* n : names) known += (known.empty() ? "" : ", ") + std::string(n);
      fail(function + "() has no argument '" + key + "'" + (known.empty() ? "" : " (its arguments: " + known + ")"));
    }
    auto& slot = bound[static_cast<std::size_t>(it - names.begin())];
    if (slot) fail(function + "() got argument '" + key + "' twice");
    slot = value;
  }
  for (std::size_t i = 0; i < required; ++i) {
    if (!bound[i]) fail(function + "() is missing its argument '" + names[i] + "'");
  }
  return bound;
}

namespace {

double numberArgument(const std::string& fn, const Value& v) {
  if (!v.isNumber()) fail(fn + "() needs a number, got " + aTypeName(v) + " (" + repr(v) + ")");
  return asDouble(v);
}

// Python's whitespace for int(), float() and str.split().
bool isPythonSpace(char c) { return c == ' ' || (c >= '\t' && c <= '\r') || (c >= '\x1c' && c <= '\x1f'); }

std::string withoutSurroundingSpace(const std::string& text) {
  std::size_t begin = 0;
  std::size_t end = text.size();
  while (begin < end && isPythonSpace(text[begin])) ++begin;
  while (end > begin && isPythonSpace(text[end - 1])) --end;
  return text.substr(begin, end - begin);
}

// Python allows one underscore between two digits of a number ("1_000");
// nullopt if an underscore stands anywhere else.
std::optional<std::string> withoutDigitUnderscores(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '_') {
      out += text[i];
      continue;
    }
    if (i == 0 || i + 1 >= text.size() || !std::isalnum(static_cast<unsigned char>(text[i - 1])) ||
        !std::isalnum(static_cast<unsigned char>(text[i + 1]))) {
      return std::nullopt;
    }
  }
  return out;
}

Value intOfText(const std::string& text, long long base) {
  const std::string trimmed = withoutSurroundingSpace(text);
  const std::optional<std::string> digits = withoutDigitUnderscores(trimmed);
  std::string_view view = digits ? std::string_view(*digits) : std::string_view();
  bool negative = false;
  if (!view.empty() && (view.front() == '+' || view.front() == '-')) {
    negative = view.front() == '-';
    view.remove_prefix(1);
  }
  unsigned long long magnitude = 0;
  const auto result = std::from_chars(view.data(), view.data() + view.size(), magnitude, static_cast<int>(base));
  if (!digits || view.empty() || result.ec == std::errc::invalid_argument || result.ptr != view.data() + view.size()) {
    fail("int() cannot read " + repr(Value::ofString(text)) + " as a base-" + std::to_string(base) + " integer");
  }
  constexpr unsigned long long kMaxMagnitude = static_cast<unsigned long long>(std::numeric_limits<long long>::max());
  if (result.ec == std::errc::result_out_of_range || magnitude > kMaxMagnitude + (negative ? 1 : 0)) {
    fail("int() of " + repr(Value::ofString(text)) + ": the number is beyond 64 bits");
  }
  if (negative) return Value::ofInt(magnitude == kMaxMagnitude + 1 ? std::numeric_limits<long long>::min()
                                                                     : -static_cast<long long>(magnitude));
  return Value::ofInt(static_cast<long long>(magnitude));
}

Value floatOfText(const std::string& text) {
  const std::string trimmed = withoutSurroundingSpace(text);
  std::string lower;
  for (const char c : trimmed) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  std::string_view body = lower;
  const bool negative = !body.empty() && body.front() == '-';
  if (!body.empty() && (body.front() == '+' || body.front() == '-')) body.remove_prefix(1);
  if (body == "inf" || body == "infinity") return Value::ofFloat(negative ? -HUGE_VAL : HUGE_VAL);
  if (body == "nan") return Value::ofFloat(std::nan(""));
  const std::optional<std::string> digits = withoutDigitUnderscores(trimmed);
  std::string_view view = digits ? std::string_view(*digits) : std::string_view();
  if (!view.empty() && view.front() == '+') view.remove_prefix(1);
  double value = 0.0;
  const auto result = std::from_chars(view.data(), view.data() + view.size(), value);
  // from_chars reads hexadecimal and "inf" forms Python's float() does not
  // take here; a digit or a point must lead.
  const std::size_t lead = !view.empty() && view[0] == '-' ? 1 : 0;
  const bool leads_with_number =
      lead < view.size() && (std::isdigit(static_cast<unsigned char>(view[lead])) || view[lead] == '.');
  if (!digits || !leads_with_number || result.ptr != view.data() + view.size() ||
      (result.ec != std::errc() && result.ec != std::errc::result_out_of_range)) {
    fail("float() cannot read " + repr(Value::ofString(text)) + " as a number");
  }
  if (result.ec == std::errc::result_out_of_range) value = std::strtod(std::string(view).c_str(), nullptr);
  return Value::ofFloat(value);
}

Value intOf(const std::vector<std::optional<Value>>& a) {
  const Value& x = *a[0];
  if (a[1]) {
    if (x.kind != Value::Kind::String) fail("int() with a base needs a str, not " + aTypeName(x));
    if (!isIntegral(*a[1]) || toInt(*a[1]) < 2 || toInt(*a[1]) > 36) {
      fail("int() base must be an int from 2 to 36, not " + repr(*a[1]));
    }
    return intOfText(x.text, toInt(*a[1]));
  }
  if (x.kind == Value::Kind::String) return intOfText(x.text, 10);
  const double d = numberArgument("int", x);
  if (isIntegral(x)) return Value::ofInt(toInt(x));
  if (std::isnan(d)) fail("int() of nan: cannot convert float NaN to integer");
  if (std::isinf(d)) fail("int() of " + str(x) + ": cannot convert float infinity to integer");
  const double whole = std::trunc(d);
  if (whole >= 9223372036854775808.0 || whole < -9223372036854775808.0) {
    fail("int() of " + str(x) + ": the number is beyond 64 bits");
  }
  return Value::ofInt(static_cast<long long>(whole));
}

// Python's round(): halves to even, on the exact value of the double (so
// round(2.675, 2) is 2.67, as 2.675 is stored as 2.67499999...).
Value roundOf(const std::vector<std::optional<Value>>& a) {
  const Value& x = *a[0];
  const double d = numberArgument("round", x);
  const bool has_digits = a[1] && a[1]->kind != Value::Kind::None;
  if (has_digits && !isIntegral(*a[1])) fail("round() needs an int number of digits, not " + aTypeName(*a[1]));
  const long long digits = has_digits ? toInt(*a[1]) : 0;
  if (isIntegral(x)) {
    if (digits >= 0) return Value::ofInt(toInt(x));
    if (digits < -18) return Value::ofInt(0);
    long long scale = 1;
    for (long long k = 0; k < -digits; ++k) scale *= 10;
    const long long n = toInt(x);
    long long q = n / scale;
    long long r = n % scale;
    if (r < 0) {
      r += scale;
      --q;
    }
    if (2 * r > scale || (2 * r == scale && q % 2 != 0)) ++q;
    long long out = 0;
    if (__builtin_mul_overflow(q, scale, &out)) fail("round() of " + str(x) + ": the result is beyond 64 bits");
    return Value::ofInt(out);
  }
  if (!has_digits) {
    if (std::isnan(d)) fail("round() of nan: cannot convert float NaN to integer");
    if (std::isinf(d)) fail("round() of " + str(x) + ": cannot convert float infinity to integer");
    const double r = std::nearbyint(d);
    if (r >= 9223372036854775808.0 || r < -9223372036854775808.0) fail("round() of " + str(x) + ": beyond 64 bits");
    return Value::ofInt(static_cast<long long>(r));
  }
  if (!std::isfinite(d) || digits > 330) return Value::ofFloat(d);
  if (digits >= 0) {
    // printf rounds the exact binary value correctly, halves to even.
    char buffer[1024];  // a double's 309 integer digits and at most 330 after the point
    std::snprintf(buffer, sizeof buffer, "%.*f", static_cast<int>(digits), d);
    return Value::ofFloat(std::strtod(buffer, nullptr));
  }
  if (digits < -330) return Value::ofFloat(std::copysign(0.0, d));
  const double scale = std::pow(10.0, static_cast<double>(-digits));
  return Value::ofFloat(std::nearbyint(d / scale) * scale);
}

std::vector<Value> itemsOf(const std::string& fn, const Value& v) {
  switch (v.kind) {
    case Value::Kind::List: return *v.list;
    case Value::Kind::String: {
      std::vector<Value> chars;
      for (const char c : v.text) chars.push_back(Value::ofString(std::string(1, c)));
      return chars;
    }
    case Value::Kind::Dict: {
      std::vector<Value> keys;
      for (const auto& kv : *v.dict) keys.push_back(Value::ofString(kv.first));
      return keys;
    }
    default: fail(fn + "() needs a list, str or dict, not " + aTypeName(v) + " (" + repr(v) + ")");
  }
}

Value minMaxSum(const std::string& fn, const Arguments& args) {
  if (!args.keyword.empty()) fail(fn + "() takes no keyword arguments here (key= and default= are not supported)");
  if (args.positional.empty()) fail(fn + "() needs at least one argument");
  const std::vector<Value> items = args.positional.size() == 1 || fn == "sum" ? itemsOf(fn, args.positional[0])
                                                                             : args.positional;
  if (fn == "sum") {
    if (args.positional.size() > 2) fail("sum() takes at most 2 arguments");
    Value total = args.positional.size() == 2 ? args.positional[1] : Value::ofInt(0);
    for (const auto& v : items) total = binaryOp("+", total, v);
    return total;
  }
  if (items.empty()) fail(fn + "() of an empty " + typeName(args.positional[0]));
  Value best = items[0];
  for (const auto& v : items) {
    if (compare(fn == "min" ? "<" : ">", v, best)) best = v;
  }
  return best;
}

Value absoluteValue(const Value& x) {
  if (isIntegral(x)) {
    if (toInt(x) == std::numeric_limits<long long>::min()) return Value::ofFloat(9223372036854775808.0);
    return Value::ofInt(std::llabs(toInt(x)));
  }
  if (x.kind != Value::Kind::Float) fail("abs() needs a number, got " + aTypeName(x) + " (" + repr(x) + ")");
  return Value::ofFloat(std::fabs(x.real));
}

// xacro.message/warning/error: xacro prints the text and the expression gives ''.
Value xacroMessage(const std::string& fn, const Arguments& args) {
  std::string text;
  for (const Value& v : args.positional) text += (text.empty() ? "" : " ") + str(v);
  if (fn == "fatal") fail("xacro.fatal: " + text);
  if (fn == "message") logger().info("xacro: {}", text);
  if (fn == "warning") logger().warn("xacro: warning: {}", text);
  if (fn == "error") logger().error("xacro: error: {}", text);
  return Value::ofString("");
}

double mathOfOne(const std::string& fn, double x) {
  static const std::map<std::string, double (*)(double)> kUnary = {
      {"sin", [](double v) { return std::sin(v); }},     {"cos", [](double v) { return std::cos(v); }},
      {"tan", [](double v) { return std::tan(v); }},     {"asin", [](double v) { return std::asin(v); }},
      {"acos", [](double v) { return std::acos(v); }},   {"atan", [](double v) { return std::atan(v); }},
      {"sinh", [](double v) { return std::sinh(v); }},   {"cosh", [](double v) { return std::cosh(v); }},
      {"tanh", [](double v) { return std::tanh(v); }},   {"exp", [](double v) { return std::exp(v); }},
      {"log10", [](double v) { return std::log10(v); }}, {"fabs", [](double v) { return std::fabs(v); }},
      {"radians", [](double v) { return v * M_PI / 180.0; }},
      {"degrees", [](double v) { return v * 180.0 / M_PI; }}};
  return kUnary.at(fn)(x);
}

bool isMathOfOne(const std::string& fn) {
  static const char* const kNames[] = {"sin",  "cos", "tan", "asin",  "acos", "atan",    "sinh",
                                       "cosh", "tanh", "exp", "log10", "fabs", "radians", "degrees"};
  return std::any_of(std::begin(kNames), std::end(kNames), [&](const char* n) { return fn == n; });
}

}  // namespace

Value callFunction(const std::string& written, const Arguments& args, Names& names) {
  // math.*, python.* and xacro.* name the same functions as their bare names.
  std::string fn = written;
  for (const char* prefix : {"math.", "xacro.", "python."}) {
    if (fn.rfind(prefix, 0) == 0) fn = fn.substr(std::string(prefix).size());
  }
  auto bind = [&](std::initializer_list<const char*> parameters, std::size_t required) {
    return bindArguments(written, args, parameters, required);
  };
  if (isMathOfOne(fn)) return Value::ofFloat(mathOfOne(fn, numberArgument(written, *bind({"x"}, 1)[0])));
  if (fn == "sqrt") {
    const double x = numberArgument(written, *bind({"x"}, 1)[0]);
    if (x < 0) fail(written + "() of a negative number (" + str(Value::ofFloat(x)) + ")");
    return Value::ofFloat(std::sqrt(x));
  }
  if (fn == "log") {
    const auto a = bind({"x", "base"}, 1);
    const double x = numberArgument(written, *a[0]);
    if (x <= 0) fail(written + "() of a number <= 0 (" + repr(*a[0]) + ")");
    return Value::ofFloat(a[1] ? std::log(x) / std::log(numberArgument(written, *a[1])) : std::log(x));
  }
  if (fn == "atan2" || fn == "pow" || fn == "hypot" || fn == "fmod") {
    const auto a = bind({"x", "y"}, 2);
    const double x = numberArgument(written, *a[0]);
    const double y = numberArgument(written, *a[1]);
    if (fn == "atan2") return Value::ofFloat(std::atan2(x, y));
    if (fn == "hypot") return Value::ofFloat(std::hypot(x, y));
    if (fn == "fmod") return Value::ofFloat(std::fmod(x, y));
    return Value::ofFloat(std::pow(x, y));
  }
  if (fn == "floor" || fn == "ceil" || fn == "trunc") {
    const Value x = *bind({"x"}, 1)[0];
    if (isIntegral(x)) return Value::ofInt(toInt(x));
    const double d = numberArgument(written, x);
    return intOf({Value::ofFloat(fn == "floor" ? std::floor(d) : fn == "ceil" ? std::ceil(d) : std::trunc(d)),
                  std::nullopt});
  }
  if (fn == "abs") return absoluteValue(*bind({"x"}, 1)[0]);
  if (fn == "round") return roundOf(bind({"number", "ndigits"}, 1));
  if (fn == "min" || fn == "max" || fn == "sum") return minMaxSum(fn, args);
  if (fn == "int") return intOf(bind({"x", "base"}, 1));
  if (fn == "float") {
    const auto a = bind({"x"}, 0);
    if (!a[0]) return Value::ofFloat(0.0);
    if (a[0]->kind == Value::Kind::String) return floatOfText(a[0]->text);
    return Value::ofFloat(numberArgument(written, *a[0]));
  }
  if (fn == "bool") {
    const auto a = bind({"x"}, 0);
    return Value::ofBool(a[0] && truthy(*a[0]));
  }
  if (fn == "str") {
    const auto a = bind({"object"}, 0);
    return Value::ofString(a[0] ? str(*a[0]) : "");
  }
  if (fn == "len") {
    const Value x = *bind({"obj"}, 1)[0];
    if (x.kind == Value::Kind::String) return Value::ofInt(static_cast<long long>(x.text.size()));
    if (x.kind == Value::Kind::List) return Value::ofInt(static_cast<long long>(x.list->size()));
    if (x.kind == Value::Kind::Dict) return Value::ofInt(static_cast<long long>(x.dict->size()));
    fail("len() of " + aTypeName(x) + " (" + repr(x) + "); len() takes a str, list or dict");
  }
  if (fn == "list") {
    const auto a = bind({"iterable"}, 0);
    return Value::ofList(a[0] ? itemsOf(written, *a[0]) : std::vector<Value>{});
  }
  if (fn == "load_yaml") {
    const Value file = *bind({"filename"}, 1)[0];
    if (file.kind != Value::Kind::String) fail("load_yaml() needs a file name, not " + aTypeName(file));
    return names.loadYaml(file.text);
  }
  if (written.rfind("xacro.", 0) == 0 && (fn == "message" || fn == "warning" || fn == "error" || fn == "fatal")) {
    return xacroMessage(fn, args);
  }
  fail("unknown function '" + written +
       "'; xacro's expressions call Python's str, int, float, bool, len, list, min, max, sum, abs, round, the "
       "math functions (sqrt, sin, radians, floor, ...), xacro.load_yaml and xacro.message/warning/error/fatal, "
       "and methods of values such as 'a b'.split(' ')");
}

}  // namespace servoloop::xacro
