#include "xacro_methods.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

#include "xacro_operators.hpp"

namespace servoloop::xacro {
namespace {

constexpr std::array<std::string_view, 14> kStringMethods = {
    "split", "rsplit", "join",       "format",   "strip", "lstrip", "rstrip",
    "replace", "lower", "upper", "startswith", "endswith", "find", "count"};
constexpr std::array<std::string_view, 2> kListMethods = {"index", "count"};
constexpr std::array<std::string_view, 3> kDictMethods = {"keys", "values", "get"};

[[noreturn]] void failTooLong(const std::string& call) {
  fail(call + " would make a string over " + std::to_string(kMaxStringBytes) + " bytes");
}

template <std::size_t N>
bool contains(const std::array<std::string_view, N>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

template <std::size_t N>
std::string joined(const std::array<std::string_view, N>& names) {
  std::string text;
  for (const std::string_view name : names) text += (text.empty() ? "" : ", ") + std::string(name);
  return text;
}

// ----- arguments -----

const std::string& textArgument(const std::string& call, const char* what, const Value& v) {
  if (v.kind != Value::Kind::String) fail(call + ": " + what + " must be a str, not " + aTypeName(v) + " (" + repr(v) + ")");
  return v.text;
}

long long intArgument(const std::string& call, const char* what, const Value& v) {
  if (!isIntegral(v)) fail(call + ": " + what + " must be an int, not " + aTypeName(v) + " (" + repr(v) + ")");
  return toInt(v);
}

std::optional<long long> optionalInt(const std::string& call, const char* what, const std::optional<Value>& v) {
  if (!v || v->kind == Value::Kind::None) return std::nullopt;
  return intArgument(call, what, *v);
}

// The part of `text` that text[start:end] names (for find, count,
// startswith, endswith), or nullopt when start lies past the end: Python
// finds nothing there, not even ''.
std::optional<std::string_view> window(const std::string& text, const std::string& call,
                                       const std::optional<Value>& start_arg, const std::optional<Value>& end_arg,
                                       std::size_t& offset) {
  const long long length = static_cast<long long>(text.size());
  long long start = optionalInt(call, "start", start_arg).value_or(0);
  long long end = optionalInt(call, "end", end_arg).value_or(length);
  if (start < 0) start = std::max(start + length, 0LL);
  if (end > length) end = length;
  if (end < 0) end = std::max(end + length, 0LL);
  if (start > end) return std::nullopt;
  offset = static_cast<std::size_t>(start);
  return std::string_view(text).substr(offset, static_cast<std::size_t>(end - start));
}

// ----- str -----

bool isSpace(char c) { return c == ' ' || (c >= '\t' && c <= '\r') || (c >= '\x1c' && c <= '\x1f'); }

Value stringList(std::vector<std::string> parts) {
  std::vector<Value> items;
  items.reserve(parts.size());
  for (auto& part : parts) items.push_back(Value::ofString(std::move(part)));
  return Value::ofList(std::move(items));
}

// str.split / str.rsplit. Without a separator, runs of whitespace separate
// and empty parts are dropped; with one, every occurrence separates.
Value split(const std::string& text, const std::optional<Value>& sep_arg, long long max_split, bool from_right,
            const std::string& call) {
  std::vector<std::string> parts;
  if (max_split < 0) max_split = std::numeric_limits<long long>::max();
  if (!sep_arg || sep_arg->kind == Value::Kind::None) {
    if (!from_right) {
      std::size_t i = 0;
      while (true) {
        while (i < text.size() && isSpace(text[i])) ++i;
        if (i >= text.size()) break;
        if (static_cast<long long>(parts.size()) == max_split) {
          parts.push_back(text.substr(i));  // the rest keeps its trailing whitespace, as in Python
          break;
        }
        std::size_t j = i;
        while (j < text.size() && !isSpace(text[j])) ++j;
        parts.push_back(text.substr(i, j - i));
        i = j;
      }
    } else {
      std::size_t i = text.size();
      while (true) {
        while (i > 0 && isSpace(text[i - 1])) --i;
        if (i == 0) break;
        if (static_cast<long long>(parts.size()) == max_split) {
          parts.push_back(text.substr(0, i));
          break;
        }
        std::size_t j = i;
        while (j > 0 && !isSpace(text[j - 1])) --j;
        parts.push_back(text.substr(j, i - j));
        i = j;
      }
      std::reverse(parts.begin(), parts.end());
    }
    return stringList(std::move(parts));
  }
  const std::string& sep = textArgument(call, "the separator", *sep_arg);
  if (sep.empty()) fail(call + ": empty separator; use split() to split at whitespace");
  if (!from_right) {
    std::size_t i = 0;
    for (long long n = 0; n < max_split; ++n) {
      const std::size_t at = text.find(sep, i);
      if (at == std::string::npos) break;
      parts.push_back(text.substr(i, at - i));
      i = at + sep.size();
    }
    parts.push_back(text.substr(i));
  } else {
    std::size_t end = text.size();
    for (long long n = 0; n < max_split && end >= sep.size(); ++n) {
      const std::size_t at = text.rfind(sep, end - sep.size());
      if (at == std::string::npos) break;
      parts.push_back(text.substr(at + sep.size(), end - at - sep.size()));
      end = at;
    }
    parts.push_back(text.substr(0, end));
    std::reverse(parts.begin(), parts.end());
  }
  return stringList(std::move(parts));
}

Value join(const std::string& sep, const Value& iterable, const std::string& call) {
  std::vector<Value> items;
  if (iterable.kind == Value::Kind::List) {
    items = *iterable.list;
  } else if (iterable.kind == Value::Kind::String) {
    for (const char c : iterable.text) items.push_back(Value::ofString(std::string(1, c)));
  } else if (iterable.kind == Value::Kind::Dict) {
    for (const auto& kv : *iterable.dict) items.push_back(Value::ofString(kv.first));
  } else {
    fail(call + ": join() needs a list of str, not " + aTypeName(iterable) + " (" + repr(iterable) + ")");
  }
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (items[i].kind != Value::Kind::String) {
      fail(call + ": join() needs str items; item " + std::to_string(i) + " is " + aTypeName(items[i]) + " (" +
           repr(items[i]) + "); convert it with str()");
    }
    out += (i == 0 ? "" : sep) + items[i].text;
    if (out.size() > kMaxStringBytes) failTooLong(call);
  }
  return Value::ofString(out);
}

Value strip(const std::string& text, const std::optional<Value>& chars_arg, bool left, bool right,
            const std::string& call) {
  const bool whitespace = !chars_arg || chars_arg->kind == Value::Kind::None;
  const std::string chars = whitespace ? "" : textArgument(call, "the characters", *chars_arg);
  auto strippable = [&](char c) { return whitespace ? isSpace(c) : chars.find(c) != std::string::npos; };
  std::size_t begin = 0;
  std::size_t end = text.size();
  while (left && begin < end && strippable(text[begin])) ++begin;
  while (right && end > begin && strippable(text[end - 1])) --end;
  return Value::ofString(text.substr(begin, end - begin));
}

Value replace(const std::string& text, const std::string& old, const std::string& replacement, long long max_count,
              const std::string& call) {
  if (max_count < 0) max_count = std::numeric_limits<long long>::max();
  std::string out;
  if (old.empty()) {
    // Python puts the replacement before every character and at the end.
    long long n = 0;
    for (std::size_t i = 0; i <= text.size() && out.size() <= kMaxStringBytes; ++i) {
      if (n < max_count) {
        out += replacement;
        ++n;
      }
      if (i < text.size()) out += text[i];
    }
    if (out.size() > kMaxStringBytes) failTooLong(call);
    return Value::ofString(out);
  }
  std::size_t i = 0;
  for (long long n = 0; n < max_count; ++n) {
    if (out.size() > kMaxStringBytes) break;
    const std::size_t at = text.find(old, i);
    if (at == std::string::npos) break;
    out.append(text, i, at - i);
    out += replacement;
    i = at + old.size();
  }
  out.append(text, i, std::string::npos);
  if (out.size() > kMaxStringBytes) failTooLong(call);
  return Value::ofString(out);
}

long long countOf(std::string_view text, const std::string& sub) {
  if (sub.empty()) return static_cast<long long>(text.size()) + 1;
  long long n = 0;
  for (std::size_t at = text.find(sub); at != std::string_view::npos; at = text.find(sub, at + sub.size())) ++n;
  return n;
}

// ----- str.format -----

// One replacement field's format spec: [[fill]align][sign][0][width][,|_][.precision][type].
struct FormatSpec {
  char fill = ' ';
  char align = 0;  // < > ^ =, or 0 for the type's default
  char sign = '-';
  std::size_t width = 0;
  char grouping = 0;
  std::optional<int> precision;
  char type = 0;
};

FormatSpec parseSpec(const std::string& spec, const std::string& call) {
  FormatSpec f;
  std::size_t i = 0;
  auto isAlign = [](char c) { return c == '<' || c == '>' || c == '^' || c == '='; };
  if (spec.size() >= 2 && isAlign(spec[1])) {
    f.fill = spec[0];
    f.align = spec[1];
    i = 2;
  } else if (!spec.empty() && isAlign(spec[0])) {
    f.align = spec[0];
    i = 1;
  }
  if (i < spec.size() && (spec[i] == '+' || spec[i] == '-' || spec[i] == ' ')) f.sign = spec[i++];
  if (i < spec.size() && spec[i] == '#') fail(call + ": the alternate form '#' in format spec '" + spec + "' is not supported");
  if (i < spec.size() && spec[i] == '0') {
    if (f.align == 0) {
      f.fill = '0';
      f.align = '=';
    }
    ++i;
  }
  while (i < spec.size() && std::isdigit(static_cast<unsigned char>(spec[i]))) {
    f.width = f.width * 10 + static_cast<std::size_t>(spec[i++] - '0');
    if (f.width > 1000) fail(call + ": width in format spec '" + spec + "' is over 1000");
  }
  if (i < spec.size() && (spec[i] == ',' || spec[i] == '_')) f.grouping = spec[i++];
  if (i < spec.size() && spec[i] == '.') {
    ++i;
    int precision = 0;
    const std::size_t digits_start = i;
    while (i < spec.size() && std::isdigit(static_cast<unsigned char>(spec[i]))) {
      precision = precision * 10 + (spec[i++] - '0');
      if (precision > 300) fail(call + ": precision in format spec '" + spec + "' is over 300");
    }
    if (i == digits_start) fail(call + ": format spec '" + spec + "' has a '.' without a precision");
    f.precision = precision;
  }
  if (i < spec.size()) f.type = spec[i++];
  if (i < spec.size()) fail(call + ": invalid format spec '" + spec + "'");
  return f;
}

// Thousands separators in the integer digits of `digits` (which may hold a
// fraction or exponent after them).
std::string grouped(const std::string& digits, char separator) {
  std::size_t end = 0;
  while (end < digits.size() && std::isdigit(static_cast<unsigned char>(digits[end]))) ++end;
  std::string out;
  for (std::size_t i = 0; i < end; ++i) {
    if (i > 0 && (end - i) % 3 == 0) out += separator;
    out += digits[i];
  }
  return out + digits.substr(end);
}

std::string printed(const char* format, int precision, double x) {
  char buffer[1024];  // a double's 309 integer digits and a precision of at most 300
  std::snprintf(buffer, sizeof buffer, format, precision, x);
  return buffer;
}

// The digits of a float (without its sign) for types f, e, g, %, and none.
std::string floatDigits(double x, const FormatSpec& f, const std::string& call, const Value& v) {
  const char type = f.type;
  const bool upper = type == 'F' || type == 'E' || type == 'G';
  if (std::isnan(x) || std::isinf(x)) {
    std::string word = std::isnan(x) ? "nan" : "inf";
    if (upper) std::transform(word.begin(), word.end(), word.begin(), ::toupper);
    return type == '%' ? word + "%" : word;
  }
  const double a = std::fabs(x);
  switch (type) {
    case 'f':
    case 'F': return printed("%.*f", f.precision.value_or(6), a);
    case 'e': return printed("%.*e", f.precision.value_or(6), a);
    case 'E': return printed("%.*E", f.precision.value_or(6), a);
    case 'g': return printed("%.*g", std::max(f.precision.value_or(6), 1), a);
    case 'G': return printed("%.*G", std::max(f.precision.value_or(6), 1), a);
    case '%': return printed("%.*f", f.precision.value_or(6), a * 100.0) + "%";
    case 0: {
      if (!f.precision) {
        const std::string text = str(Value::ofFloat(a));
        return text;
      }
      // Like 'g', but scientific from an exponent of precision - 1 on, and a
      // fixed-point result keeps one digit after the point.
      const int p = std::max(*f.precision, 1);
      const std::string sci = printed("%.*e", p - 1, a);
      const int exponent = std::atoi(sci.c_str() + sci.find('e') + 1);
      if (exponent < -4 || exponent >= p - 1) {
        std::string mantissa = sci.substr(0, sci.find('e'));
        if (mantissa.find('.') != std::string::npos) {
          mantissa.erase(mantissa.find_last_not_of('0') + 1);
          if (mantissa.back() == '.') mantissa.pop_back();
        }
        return mantissa + sci.substr(sci.find('e'));
      }
      std::string fixed = printed("%.*f", p - 1 - exponent, a);
      if (fixed.find('.') != std::string::npos) {
        fixed.erase(fixed.find_last_not_of('0') + 1);
        if (fixed.back() == '.') fixed += '0';
      } else {
        fixed += ".0";
      }
      return fixed;
    }
    default:
      fail(call + ": unknown format code '" + std::string(1, type) + "' for " + aTypeName(v) + " (" + repr(v) + ")");
  }
}

std::string padded(const std::string& sign, const std::string& body, const FormatSpec& f, char default_align) {
  const std::size_t length = sign.size() + body.size();
  if (f.width <= length) return sign + body;
  const std::size_t pad = f.width - length;
  switch (f.align != 0 ? f.align : default_align) {
    case '<': return sign + body + std::string(pad, f.fill);
    case '^': return std::string(pad / 2, f.fill) + sign + body + std::string(pad - pad / 2, f.fill);
    case '=': return sign + std::string(pad, f.fill) + body;
    default: return std::string(pad, f.fill) + sign + body;
  }
}

// format(v, spec) as Python's built-in types do it.
std::string formatValue(const Value& v, const std::string& spec, const std::string& call) {
  if (spec.empty()) return str(v);
  const FormatSpec f = parseSpec(spec, call);
  if (v.kind == Value::Kind::String || v.kind == Value::Kind::None || v.kind == Value::Kind::List ||
      v.kind == Value::Kind::Dict) {
    if (v.kind != Value::Kind::String && (f.type != 0 || f.precision)) {
      fail(call + ": format spec '" + spec + "' does not apply to " + aTypeName(v));
    }
    if (f.type != 0 && f.type != 's') {
      fail(call + ": unknown format code '" + std::string(1, f.type) + "' for a str (" + repr(v) + ")");
    }
    if (f.sign != '-') fail(call + ": a sign is not allowed in format spec '" + spec + "' of a str");
    if (f.align == '=') fail(call + ": '=' alignment is not allowed in format spec '" + spec + "' of a str");
    if (f.grouping != 0) fail(call + ": cannot use '" + std::string(1, f.grouping) + "' with a str");
    std::string text = str(v);
    if (f.precision) text = text.substr(0, static_cast<std::size_t>(*f.precision));
    return padded("", text, f, '<');
  }
  const bool negative = isIntegral(v) ? toInt(v) < 0 : std::signbit(v.real);
  const std::string sign = negative ? "-" : (f.sign == '+' ? "+" : (f.sign == ' ' ? " " : ""));
  std::string body;
  const bool integer_type = f.type == 0 || f.type == 'd' || f.type == 'x' || f.type == 'X' || f.type == 'o' ||
                            f.type == 'b' || f.type == 'n';
  if (isIntegral(v) && integer_type) {
    if (f.precision) fail(call + ": precision is not allowed in format spec '" + spec + "' of an int");
    const long long n = toInt(v);
    const unsigned long long magnitude =
        n < 0 ? 0ULL - static_cast<unsigned long long>(n) : static_cast<unsigned long long>(n);
    const int base = f.type == 'x' || f.type == 'X' ? 16 : f.type == 'o' ? 8 : f.type == 'b' ? 2 : 10;
    char buffer[80];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, magnitude, base).ptr;
    body.assign(buffer, end);
    if (f.type == 'X') std::transform(body.begin(), body.end(), body.begin(), ::toupper);
  } else if (!isIntegral(v) && (f.type == 'd' || f.type == 'x' || f.type == 'X' || f.type == 'o' || f.type == 'b')) {
    fail(call + ": unknown format code '" + std::string(1, f.type) + "' for a float (" + repr(v) +
         "); use 'f', or convert with int()");
  } else if (f.type == 's') {
    fail(call + ": unknown format code 's' for " + aTypeName(v) + " (" + repr(v) + "); convert with str()");
  } else {
    body = floatDigits(asDouble(v), f, call, v);
  }
  if (f.grouping != 0) body = grouped(body, f.grouping);
  return padded(sign, body, f, '>');
}

Value format(const std::string& pattern, const Arguments& args, const std::string& call) {
  std::string out;
  std::size_t next_auto = 0;
  bool used_auto = false;
  bool used_manual = false;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    const char c = pattern[i];
    if (c == '}') {
      if (i + 1 < pattern.size() && pattern[i + 1] == '}') {
        out += '}';
        ++i;
        continue;
      }
      fail(call + ": single '}' in the format string; write '}}' for a literal '}'");
    }
    if (c != '{') {
      out += c;
      continue;
    }
    if (i + 1 < pattern.size() && pattern[i + 1] == '{') {
      out += '{';
      ++i;
      continue;
    }
    const std::size_t close = pattern.find('}', i);
    if (close == std::string::npos) fail(call + ": a '{' in the format string is not closed; write '{{' for a literal '{'");
    const std::string field = pattern.substr(i + 1, close - i - 1);
    if (field.find('{') != std::string::npos) fail(call + ": nested fields ('" + field + "') are not supported");
    const std::size_t name_end = field.find_first_of("!:");
    const std::string name = field.substr(0, name_end);
    std::string conversion;
    std::string spec;
    if (name_end != std::string::npos && field[name_end] == '!') {
      const std::size_t colon = field.find(':', name_end);
      conversion = field.substr(name_end + 1, colon == std::string::npos ? std::string::npos : colon - name_end - 1);
      if (colon != std::string::npos) spec = field.substr(colon + 1);
    } else if (name_end != std::string::npos) {
      spec = field.substr(name_end + 1);
    }
    Value value;
    if (name.empty()) {
      if (used_manual) fail(call + ": cannot switch from manual field numbering ({0}) to automatic ({})");
      used_auto = true;
      if (next_auto >= args.positional.size()) {
        fail(call + ": the format string has more {} fields than the " + std::to_string(args.positional.size()) +
             " argument(s) given");
      }
      value = args.positional[next_auto++];
    } else if (std::all_of(name.begin(), name.end(), [](char d) { return std::isdigit(static_cast<unsigned char>(d)); })) {
      if (used_auto) fail(call + ": cannot switch from automatic field numbering ({}) to manual ({" + name + "})");
      used_manual = true;
      const std::size_t index = name.size() > 6 ? std::string::npos : std::stoul(name);
      if (index >= args.positional.size()) {
        fail(call + ": field {" + name + "} is beyond the " + std::to_string(args.positional.size()) +
             " argument(s) given (they count from 0)");
      }
      value = args.positional[index];
    } else {
      const auto it = std::find_if(args.keyword.begin(), args.keyword.end(), [&](const auto& kv) { return kv.first == name; });
      if (it == args.keyword.end()) {
        if (name.find_first_of(".[") != std::string::npos) {
          fail(call + ": field {" + name + "}: servoloop's xacro formats {}, {0} and {name}; index the value in the "
                      "arguments instead, e.g. '{}'.format(v[0])");
        }
        fail(call + ": field {" + name + "} has no argument; pass " + name + "=...");
      }
      value = it->second;
    }
    if (conversion == "r" || conversion == "a") {
      value = Value::ofString(repr(value));
    } else if (conversion == "s") {
      value = Value::ofString(str(value));
    } else if (!conversion.empty()) {
      fail(call + ": unknown conversion '!" + conversion + "'; use !s or !r");
    }
    out += formatValue(value, spec, call);
    if (out.size() > kMaxStringBytes) failTooLong(call);
    i = close;
  }
  return Value::ofString(out);
}

Value stringMethod(const std::string& text, const std::string& method, const Arguments& args, const std::string& call) {
  auto bind = [&](std::initializer_list<const char*> parameters, std::size_t required) {
    return bindArguments(call, args, parameters, required);
  };
  if (method == "split" || method == "rsplit") {
    const auto a = bind({"sep", "maxsplit"}, 0);
    return split(text, a[0], a[1] ? intArgument(call, "maxsplit", *a[1]) : -1, method == "rsplit", call);
  }
  if (method == "join") return join(text, *bind({"iterable"}, 1)[0], call);
  if (method == "format") return format(text, args, call);
  if (method == "strip" || method == "lstrip" || method == "rstrip") {
    return strip(text, bind({"chars"}, 0)[0], method != "rstrip", method != "lstrip", call);
  }
  if (method == "replace") {
    const auto a = bind({"old", "new", "count"}, 2);
    return replace(text, textArgument(call, "the old text", *a[0]), textArgument(call, "the new text", *a[1]),
                   a[2] ? intArgument(call, "count", *a[2]) : -1, call);
  }
  if (method == "lower" || method == "upper") {
    bind({}, 0);
    std::string out = text;
    for (char& c : out) c = static_cast<char>(method == "lower" ? std::tolower(static_cast<unsigned char>(c))
                                                                 : std::toupper(static_cast<unsigned char>(c)));
    return Value::ofString(out);
  }
  if (method == "startswith" || method == "endswith") {
    const auto a = bind({"prefix", "start", "end"}, 1);
    const std::string& part = textArgument(call, method == "startswith" ? "the prefix" : "the suffix", *a[0]);
    std::size_t offset = 0;
    const std::optional<std::string_view> view = window(text, call, a[1], a[2], offset);
    const bool match = view && part.size() <= view->size() &&
                       (method == "startswith" ? view->substr(0, part.size()) == part
                                               : view->substr(view->size() - part.size()) == part);
    return Value::ofBool(match);
  }
  if (method == "find") {
    const auto a = bind({"sub", "start", "end"}, 1);
    const std::string& sub = textArgument(call, "the text to find", *a[0]);
    std::size_t offset = 0;
    const std::optional<std::string_view> view = window(text, call, a[1], a[2], offset);
    const std::size_t at = view ? view->find(sub) : std::string_view::npos;
    return Value::ofInt(at == std::string_view::npos ? -1 : static_cast<long long>(offset + at));
  }
  if (method == "count") {
    const auto a = bind({"sub", "start", "end"}, 1);
    const std::string& sub = textArgument(call, "the text to count", *a[0]);
    std::size_t offset = 0;
    const std::optional<std::string_view> view = window(text, call, a[1], a[2], offset);
    return Value::ofInt(view ? countOf(*view, sub) : 0);
  }
  fail(call + ": a str has no method '" + method + "' (servoloop's xacro knows " + joined(kStringMethods) + ")");
}

Value listMethod(const std::vector<Value>& items, const std::string& method, const Arguments& args,
                 const std::string& call) {
  const Value x = *bindArguments(call, args, {"value"}, 1)[0];
  if (method == "count") {
    return Value::ofInt(static_cast<long long>(
        std::count_if(items.begin(), items.end(), [&](const Value& item) { return equal(item, x); })));
  }
  if (method == "index") {
    const auto it = std::find_if(items.begin(), items.end(), [&](const Value& item) { return equal(item, x); });
    if (it == items.end()) fail(call + ": " + repr(x) + " is not in the list " + str(Value::ofList(items)));
    return Value::ofInt(static_cast<long long>(it - items.begin()));
  }
  fail(call + ": a list has no method '" + method + "' (servoloop's xacro knows " + joined(kListMethods) + ")");
}

Value dictMethod(const Value& dict, const std::string& method, const Arguments& args, const std::string& call) {
  if (method == "keys" || method == "values") {
    bindArguments(call, args, {}, 0);
    std::vector<Value> items;
    for (const auto& [key, item] : *dict.dict) items.push_back(method == "keys" ? Value::ofString(key) : item);
    return Value::ofList(std::move(items));
  }
  if (method == "get") {
    const auto a = bindArguments(call, args, {"key", "default"}, 1);
    const Value* found = dict.find(str(*a[0]));
    return found != nullptr ? *found : a[1].value_or(Value::none());
  }
  fail(call + ": a dict has no method '" + method + "' (servoloop's xacro knows " + joined(kDictMethods) +
       "; a key is read with d['" + method + "'])");
}

}  // namespace

bool hasMethod(const Value& receiver, const std::string& method) {
  switch (receiver.kind) {
    case Value::Kind::String: return contains(kStringMethods, method);
    case Value::Kind::List: return contains(kListMethods, method);
    case Value::Kind::Dict: return contains(kDictMethods, method);
    default: return false;
  }
}

std::string methodNames(const Value& receiver) {
  switch (receiver.kind) {
    case Value::Kind::String: return joined(kStringMethods);
    case Value::Kind::List: return joined(kListMethods);
    case Value::Kind::Dict: return joined(kDictMethods);
    default: return "";
  }
}

Value callMethod(const Value& receiver, const std::string& method, const Arguments& args, const std::string& call) {
  switch (receiver.kind) {
    case Value::Kind::String: return stringMethod(receiver.text, method, args, call);
    case Value::Kind::List: return listMethod(*receiver.list, method, args, call);
    case Value::Kind::Dict: return dictMethod(receiver, method, args, call);
    default: fail(aTypeName(receiver) + " (" + repr(receiver) + ") has no method '" + method + "'");
  }
}

}  // namespace servoloop::xacro
