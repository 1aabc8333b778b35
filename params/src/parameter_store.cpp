#include "servoloop/params/parameter_store.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include <yaml-cpp/depthguard.h>

#include "servoloop/core/number_text.hpp"
#include "servoloop/core/text_file.hpp"

namespace servoloop::params {

namespace {

constexpr std::string_view kSetSource = "set";

bool isOneOf(std::string_view text, std::initializer_list<std::string_view> words) {
  return std::find(words.begin(), words.end(), text) != words.end();
}

bool isDigits(std::string_view text, bool hex) {
  if (text.empty()) return false;
  return std::all_of(text.begin(), text.end(), [hex](char c) {
    return (c >= '0' && c <= '9') || (hex && ((c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F')));
  });
}

std::string_view stripSign(std::string_view text) {
  if (!text.empty() && (text.front() == '+' || text.front() == '-')) text.remove_prefix(1);
  return text;
}

// Integer text: [-+]?[0-9]+ or [-+]?0x[0-9a-fA-F]+, value in int64 range.
std::optional<std::int64_t> parseInteger(std::string_view text) {
  const bool negative = !text.empty() && text.front() == '-';
  std::string_view digits = stripSign(text);
  int base = 10;
  if (digits.size() > 2 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) {
    digits.remove_prefix(2);
    base = 16;
  }
  if (!isDigits(digits, base == 16)) return std::nullopt;
  std::uint64_t magnitude = 0;
  auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), magnitude, base);
  if (ec != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
  constexpr auto kMax = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
  if (negative) {
    if (magnitude > kMax + 1) return std::nullopt;
    return magnitude == kMax + 1 ? std::numeric_limits<std::int64_t>::min()
                                 : -static_cast<std::int64_t>(magnitude);
  }
  if (magnitude > kMax) return std::nullopt;
  return static_cast<std::int64_t>(magnitude);
}

// Floating-point text in the YAML 1.2 core schema: 1.0, .5, 1e3, -2.5E-3,
// .inf, -.Inf, .nan (also integers too large for int64).
std::optional<double> parseFloating(std::string_view text) {
  const bool negative = !text.empty() && text.front() == '-';
  const std::string_view body = stripSign(text);
  if (isOneOf(body, {".inf", ".Inf", ".INF"})) {
    return negative ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
  }
  if (isOneOf(text, {".nan", ".NaN", ".NAN"})) return std::numeric_limits<double>::quiet_NaN();
  // Validate the shape first: strtod alone would accept "inf", "0x1p3", " 1".
  std::size_t i = 0;
  std::size_t mantissa_digits = 0;
  while (i < body.size() && std::isdigit(static_cast<unsigned char>(body[i]))) ++i, ++mantissa_digits;
  if (i < body.size() && body[i] == '.') {
    ++i;
    while (i < body.size() && std::isdigit(static_cast<unsigned char>(body[i]))) ++i, ++mantissa_digits;
  }
  if (mantissa_digits == 0) return std::nullopt;
  if (i < body.size() && (body[i] == 'e' || body[i] == 'E')) {
    ++i;
    if (i < body.size() && (body[i] == '+' || body[i] == '-')) ++i;
    const std::size_t exponent_start = i;
    while (i < body.size() && std::isdigit(static_cast<unsigned char>(body[i]))) ++i;
    if (i == exponent_start) return std::nullopt;
  }
  if (i != body.size()) return std::nullopt;
  const std::string copy(text);
  return std::strtod(copy.c_str(), nullptr);
}

std::optional<bool> parseBool(std::string_view text) {
  // YAML 1.1 booleans, as rosparam (PyYAML) reads them.
  if (isOneOf(text, {"true", "True", "TRUE", "yes", "Yes", "YES", "on", "On", "ON"})) return true;
  if (isOneOf(text, {"false", "False", "FALSE", "no", "No", "NO", "off", "Off", "OFF"})) return false;
  return std::nullopt;
}

ParamType classifyPlainScalar(std::string_view text) {
  if (isOneOf(text, {"", "~", "null", "Null", "NULL"})) return ParamType::null;
  if (parseBool(text)) return ParamType::boolean;
  if (parseInteger(text)) return ParamType::integer;
  if (parseFloating(text)) return ParamType::floating;
  return ParamType::string;
}

std::vector<std::string> splitName(std::string_view absolute_name) {
  std::vector<std::string> segments;
  std::size_t start = 0;
  while (start <= absolute_name.size()) {
    std::size_t end = absolute_name.find('/', start);
    if (end == std::string_view::npos) end = absolute_name.size();
    if (end > start) segments.emplace_back(absolute_name.substr(start, end - start));
    start = end + 1;
  }
  return segments;
}

std::string joinName(const std::string& parent, std::string_view child) {
  return resolveName(parent, child.empty() || child.front() != '/' ? child : child.substr(1));
}

std::string parentOf(const std::string& absolute_name) {
  const std::size_t slash = absolute_name.rfind('/');
  return slash == 0 || slash == std::string::npos ? std::string("/") : absolute_name.substr(0, slash);
}

std::string markText(std::string_view source, const YAML::Mark& mark) {
  if (mark.is_null()) return std::string(source);
  return std::string(source) + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

// The value of a scalar as the user wrote it, for messages: strings quoted.
std::string describeValue(const YAML::Node& value, ParamType type) {
  switch (type) {
    case ParamType::string: return "\"" + value.Scalar() + "\"";
    case ParamType::list: return "a list of " + std::to_string(value.size());
    case ParamType::map: return "a map";
    case ParamType::null: return "empty";
    default: return value.Scalar();
  }
}

std::string_view conversionHint(std::string_view expected, ParamType actual) {
  if (expected == "double" || expected == "int") {
    if (actual == ParamType::string) return "; write the number without quotes";
    if (expected == "int" && actual == ParamType::floating) return "; write it without a decimal point";
  }
  if (expected == "string" && actual != ParamType::list && actual != ParamType::map) {
    return "; quote the value to make it a string";
  }
  if (expected.starts_with("list") && actual != ParamType::list) return "; write it as a list, e.g. [1.0, 2.0]";
  return "";
}

bool isScalarString(const YAML::Node& node) {
  return node.IsScalar() && paramTypeOf(node) == ParamType::string;
}

// yaml-cpp's emitter writes every scalar plain; strings that would read back as
// another type ("10", "true") must be quoted to round-trip.
void emitValue(YAML::Emitter& out, const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Map:
      out << YAML::BeginMap;
      for (const auto& entry : node) {
        out << YAML::Key << entry.first.Scalar() << YAML::Value;
        emitValue(out, entry.second);
      }
      out << YAML::EndMap;
      break;
    case YAML::NodeType::Sequence: {
      const bool all_scalars =
          std::all_of(node.begin(), node.end(), [](const YAML::Node& item) { return item.IsScalar(); });
      if (all_scalars) out << YAML::Flow;
      out << YAML::BeginSeq;
      for (const auto& item : node) emitValue(out, item);
      out << YAML::EndSeq;
      break;
    }
    case YAML::NodeType::Scalar:
      if (isScalarString(node) && classifyPlainScalar(node.Scalar()) != ParamType::string) {
        out << YAML::DoubleQuoted << node.Scalar();
      } else {
        out << node.Scalar();
      }
      break;
    default:
      out << YAML::Null;
      break;
  }
}

void collectLeaves(const YAML::Node& node, const std::string& name, std::vector<std::string>& out) {
  if (node.IsMap() && node.size() > 0) {
    for (const auto& entry : node) collectLeaves(entry.second, joinName(name, entry.first.Scalar()), out);
  } else {
    out.push_back(name);
  }
}

YAML::Node childOf(const YAML::Node& map, const std::string& key) {
  const YAML::Node& const_map = map;  // const lookup: never inserts
  return const_map[key];
}

}  // namespace

std::string_view paramTypeName(ParamType type) {
  switch (type) {
    case ParamType::null: return "null";
    case ParamType::boolean: return "bool";
    case ParamType::integer: return "int";
    case ParamType::floating: return "double";
    case ParamType::string: return "string";
    case ParamType::list: return "list";
    case ParamType::map: return "map";
  }
  return "unknown";
}

ParamType paramTypeOf(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return ParamType::null;
  if (node.IsMap()) return ParamType::map;
  if (node.IsSequence()) return ParamType::list;
  const std::string& tag = node.Tag();
  const std::string& text = node.Scalar();
  if (tag == "!" || tag == "tag:yaml.org,2002:str") return ParamType::string;
  if (tag == "tag:yaml.org,2002:int" && parseInteger(text)) return ParamType::integer;
  if (tag == "tag:yaml.org,2002:float" && (parseFloating(text) || parseInteger(text))) return ParamType::floating;
  if (tag == "tag:yaml.org,2002:bool" && parseBool(text)) return ParamType::boolean;
  return classifyPlainScalar(text);
}

std::string resolveName(std::string_view ns, std::string_view name) {
  if (!name.empty() && name.front() == '~') {
    throw Error("name '" + std::string(name) + "': private '~' names are not supported; use the full name");
  }
  std::string combined;
  if (!name.empty() && name.front() == '/') {
    combined = std::string(name);
  } else {
    combined = std::string(ns) + "/" + std::string(name);
  }
  std::string result;
  for (const std::string& segment : splitName(combined)) result += "/" + segment;
  return result.empty() ? "/" : result;
}

void checkParameterName(std::string_view name) {
  const std::string quoted = "'" + std::string(name) + "'";
  if (name.empty()) {
    throw Error("parameter name '' is empty: an empty name stands for the whole namespace, so setting it would "
                "replace every parameter there; give the full name of one parameter, e.g. "
                "/one_DOF_robot/joint1_position_controller/pid/p");
  }
  if (name.front() == '~') {
    throw Error("parameter name " + quoted + " is a private '~' name: private names belong to a ROS node's own "
                "namespace, which a client of the servoloop node does not have; give the full name, e.g. "
                "/one_DOF_robot/" + std::string(name.substr(1)));
  }
  const auto isAlpha = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
  const auto isDigit = [](char c) { return c >= '0' && c <= '9'; };
  const bool first_ok = isAlpha(name.front()) || name.front() == '/';
  const bool rest_ok = std::all_of(name.begin(), name.end(),
                                   [&](char c) { return isAlpha(c) || isDigit(c) || c == '_' || c == '/'; });
  if (!first_ok || !rest_ok || name.size() > kMaxParameterNameLength) {
    throw Error("parameter name " + quoted.substr(0, 200) + (quoted.size() > 200 ? "...'" : "") +
                " is not a ROS graph resource name: it must start with a letter or '/', hold only letters, digits, "
                "'_' and '/', and be at most " + std::to_string(kMaxParameterNameLength) + " characters long");
  }
}

namespace {

// The absolute name a setter writes to, once the name passes checkParameterName.
std::string settableName(std::string_view name) {
  checkParameterName(name);
  return resolveName("/", name);
}

}  // namespace

namespace {

// The walk of checkYamlDocument and checkYamlSize: the node count always, the
// keys given twice when `duplicate_keys` is set.
void checkYaml(const YAML::Node& document, std::string_view source_name, bool duplicate_keys) {
  std::size_t count = 0;
  std::vector<YAML::Node> pending{document};
  while (!pending.empty()) {
    const YAML::Node node = pending.back();
    pending.pop_back();
    if (++count > kMaxYamlNodes) {
      throw ConfigError(std::string(source_name) + ": the YAML holds more than " + std::to_string(kMaxYamlNodes) +
                        " values once its aliases (*name) are expanded; no robot's YAML comes near that, so "
                        "it is refused (an alias bomb?)");
    }
    if (node.IsSequence()) {
      for (const auto& item : node) pending.push_back(item);
    } else if (node.IsMap()) {
      std::map<std::string, YAML::Mark> seen;
      for (const auto& item : node) {
        if (duplicate_keys && item.first.IsScalar()) {
          const auto [first, inserted] = seen.emplace(item.first.Scalar(), item.first.Mark());
          if (!inserted) {
            throw ConfigError(markText(std::string(source_name), item.first.Mark()) + ": key '" +
                              item.first.Scalar() + "' appears twice in one map (first at line " +
                              std::to_string(first->second.line + 1) +
                              "); ROS would use the last, yaml-cpp the first: keep one");
          }
        }
        pending.push_back(item.first);
        pending.push_back(item.second);
      }
    }
  }
}

}  // namespace

void checkYamlDocument(const YAML::Node& document, std::string_view source_name) {
  checkYaml(document, source_name, true);
}

void checkYamlSize(const YAML::Node& document, std::string_view source_name) {
  checkYaml(document, source_name, false);
}

ParameterStore::ParameterStore() : root_(YAML::NodeType::Map) {}

// --- loading -----------------------------------------------------------------

void ParameterStore::loadFile(const std::string& path, std::string_view ns) {
  loadString(readTextFile(path, "parameter file"), path, ns);
}

void ParameterStore::loadString(std::string_view yaml, std::string_view source_name, std::string_view ns) {
  const std::string source(source_name);
  YAML::Node document;
  try {
    document = YAML::Load(std::string(yaml));
  } catch (const YAML::DeepRecursion& e) {
    // yaml-cpp's parser recurses once per level and stops at a fixed depth
    // (DepthGuard): its own message ("bad file") would send the user looking
    // for a syntax error. e.depth() is the level refused, one past the limit.
    throw ConfigError(source + ": the YAML nests deeper than yaml-cpp's limit of " + std::to_string(e.depth() - 1) +
                      " levels" + (e.mark.is_null() ? "" : " (at line " + std::to_string(e.mark.line + 1) + ")") +
                      "; no parameter file needs that: flatten it");
  } catch (const YAML::Exception& e) {
    throw ConfigError(markText(source, e.mark) + ": invalid YAML: " + e.msg +
                      "; fix the syntax there (indentation, a ':' after each key, closed brackets and quotes)");
  }
  if (!document.IsDefined() || document.IsNull()) return;  // an empty file sets nothing
  checkYamlDocument(document, source);
  if (!document.IsMap()) {
    throw ConfigError(source + ": the top level is a " + std::string(paramTypeName(paramTypeOf(document))) +
                      ", expected a map of names to values (e.g. 'my_robot:' followed by indented keys)");
  }
  // The namespace names where the values go, so it follows the setters' rules.
  if (!ns.empty() && ns != "/") checkParameterName(ns);
  const std::string base = resolveName("/", ns);

  // Depth-first merge: maps merge key by key, anything else replaces.
  struct Merger {
    ParameterStore& store;
    const std::string& source;
    void merge(const std::string& name, const YAML::Node& value) {
      if (!value.IsMap()) {
        store.insertLocked(name, value, markText(source, value.Mark()));
        return;
      }
      const std::optional<YAML::Node> existing =
          store.hasLocked(name) ? std::optional<YAML::Node>(store.findLocked(name)) : std::nullopt;
      if (name != "/" && (!existing || !existing->IsMap())) {
        store.insertLocked(name, YAML::Node(YAML::NodeType::Map), markText(source, value.Mark()));
      }
      for (const auto& entry : value) {
        if (!entry.first.IsScalar() || entry.first.Scalar().empty()) {
          throw ConfigError(markText(source, entry.first.Mark()) + ": under '" + name +
                            "': a key must be a plain name, not a list, a map or empty");
        }
        merge(joinName(name, entry.first.Scalar()), entry.second);
      }
    }
  };
  std::lock_guard lock(mutex_);
  Merger{*this, source}.merge(base, document);
}

// --- lookup --------------------------------------------------------------------

bool ParameterStore::hasLocked(const std::string& absolute_name) const {
  return findLocked(absolute_name).IsDefined();
}

YAML::Node ParameterStore::findLocked(const std::string& absolute_name) const {
  YAML::Node current;
  current.reset(root_);
  for (const std::string& segment : splitName(absolute_name)) {
    if (!current.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
    YAML::Node child = childOf(current, segment);
    if (!child.IsDefined()) return YAML::Node(YAML::NodeType::Undefined);
    current.reset(child);
  }
  return current;
}

YAML::Node ParameterStore::requireLocked(const std::string& absolute_name) const {
  YAML::Node value = findLocked(absolute_name);
  if (value.IsDefined()) return value;
  // Name the deepest namespace that exists and what it holds.
  std::string parent = parentOf(absolute_name);
  while (parent != "/" && !findLocked(parent).IsDefined()) parent = parentOf(parent);
  const YAML::Node parent_node = findLocked(parent);
  std::string detail;
  if (parent_node.IsMap()) {
    std::vector<std::string> keys;
    for (const auto& entry : parent_node) keys.push_back(entry.first.Scalar());
    std::sort(keys.begin(), keys.end());
    std::string joined;
    for (const auto& key : keys) joined += (joined.empty() ? "" : ", ") + key;
    detail = keys.empty() ? "'" + parent + "' is empty"
                          : "'" + parent + "' has: " + joined;
  } else {
    detail = "'" + parent + "' is a " + std::string(paramTypeName(paramTypeOf(parent_node))) +
             ", not a namespace";
  }
  throw ParameterNotFoundError("parameter '" + absolute_name + "' not found; " + detail +
                               " (load the YAML that sets it, or check the spelling)");
}

std::string ParameterStore::sourceLocked(const std::string& absolute_name) const {
  for (std::string name = absolute_name;; name = parentOf(name)) {
    if (auto it = sources_.find(name); it != sources_.end()) return it->second;
    if (name == "/") return "";
  }
}

void ParameterStore::throwTypeError(const std::string& absolute_name, const YAML::Node& value,
                                    std::string_view expected) const {
  const ParamType actual = paramTypeOf(value);
  const std::string source = sourceLocked(absolute_name);
  throw ParameterTypeError("parameter '" + absolute_name + "'" + (source.empty() ? "" : " (" + source + ")") +
                           " is " + std::string(paramTypeName(actual)) + " " + describeValue(value, actual) +
                           ", expected " + std::string(expected) + std::string(conversionHint(expected, actual)));
}

// --- typed conversion --------------------------------------------------------------

namespace {
// Converts one scalar; returns nullopt when its type does not fit T.
template <class T>
std::optional<T> scalarAs(const YAML::Node& value);

template <>
std::optional<double> scalarAs<double>(const YAML::Node& value) {
  const ParamType type = paramTypeOf(value);
  if (type == ParamType::integer) return static_cast<double>(*parseInteger(value.Scalar()));
  if (type == ParamType::floating) {
    if (auto number = parseFloating(value.Scalar())) return number;
    return static_cast<double>(*parseInteger(value.Scalar()));  // !!float 5
  }
  return std::nullopt;
}
template <>
std::optional<std::int64_t> scalarAs<std::int64_t>(const YAML::Node& value) {
  if (paramTypeOf(value) != ParamType::integer) return std::nullopt;
  return parseInteger(value.Scalar());
}
template <>
std::optional<int> scalarAs<int>(const YAML::Node& value) {
  const auto wide = scalarAs<std::int64_t>(value);
  if (!wide || *wide < std::numeric_limits<int>::min() || *wide > std::numeric_limits<int>::max()) {
    return std::nullopt;
  }
  return static_cast<int>(*wide);
}
template <>
std::optional<bool> scalarAs<bool>(const YAML::Node& value) {
  if (paramTypeOf(value) != ParamType::boolean) return std::nullopt;
  return parseBool(value.Scalar());
}
template <>
std::optional<std::string> scalarAs<std::string>(const YAML::Node& value) {
  if (paramTypeOf(value) != ParamType::string) return std::nullopt;
  return value.Scalar();
}

}  // namespace

std::int64_t paramIntegerValue(const YAML::Node& scalar) {
  if (auto value = scalar.IsScalar() ? scalarAs<std::int64_t>(scalar) : std::nullopt) return *value;
  throw Error("expected an int, got " + std::string(paramTypeName(paramTypeOf(scalar))));
}

double paramDoubleValue(const YAML::Node& scalar) {
  if (auto value = scalar.IsScalar() ? scalarAs<double>(scalar) : std::nullopt) return *value;
  throw Error("expected a number, got " + std::string(paramTypeName(paramTypeOf(scalar))));
}

namespace {
template <class T>
constexpr std::string_view typeNameOf() {
  if constexpr (std::is_same_v<T, double>) return "double";
  if constexpr (std::is_same_v<T, int> || std::is_same_v<T, std::int64_t>) return "int";
  if constexpr (std::is_same_v<T, bool>) return "bool";
  if constexpr (std::is_same_v<T, std::string>) return "string";
  return "?";
}

template <class T>
struct IsVector : std::false_type {};
template <class E>
struct IsVector<std::vector<E>> : std::true_type {
  using Element = E;
};
}  // namespace

template <class T>
T ParameterStore::convertLocked(const std::string& absolute_name, const YAML::Node& value) const {
  if constexpr (IsVector<T>::value) {
    using Element = typename IsVector<T>::Element;
    const std::string expected = "list of " + std::string(typeNameOf<Element>());
    if (!value.IsSequence()) throwTypeError(absolute_name, value, expected);
    T result;
    result.reserve(value.size());
    for (std::size_t i = 0; i < value.size(); ++i) {
      const YAML::Node item = value[i];
      auto converted = item.IsScalar() ? scalarAs<Element>(item) : std::nullopt;
      if (!converted) {
        throwTypeError(absolute_name + "[" + std::to_string(i) + "]", item, typeNameOf<Element>());
      }
      result.push_back(*converted);
    }
    return result;
  } else {
    auto converted = value.IsScalar() ? scalarAs<T>(value) : std::nullopt;
    if (!converted) {
      if constexpr (std::is_same_v<T, int>) {
        if (scalarAs<std::int64_t>(value)) {
          throw ParameterTypeError("parameter '" + absolute_name + "' is " + value.Scalar() +
                                   ", out of range for int");
        }
      }
      throwTypeError(absolute_name, value, typeNameOf<T>());
    }
    return *converted;
  }
}

template <class T>
T ParameterStore::get(std::string_view name) const {
  const std::string absolute_name = resolveName("/", name);
  std::lock_guard lock(mutex_);
  return convertLocked<T>(absolute_name, requireLocked(absolute_name));
}

template <class T>
bool ParameterStore::tryGet(std::string_view name, T& out) const {
  const std::string absolute_name = resolveName("/", name);
  std::lock_guard lock(mutex_);
  const YAML::Node value = findLocked(absolute_name);
  if (!value.IsDefined()) return false;
  out = convertLocked<T>(absolute_name, value);
  return true;
}

#define SERVOLOOP_PARAMETER_TYPE(T)                                           \
  template T ParameterStore::get<T>(std::string_view) const;                  \
  template bool ParameterStore::tryGet<T>(std::string_view, T&) const;
SERVOLOOP_PARAMETER_TYPE(double)
SERVOLOOP_PARAMETER_TYPE(int)
SERVOLOOP_PARAMETER_TYPE(std::int64_t)
SERVOLOOP_PARAMETER_TYPE(bool)
SERVOLOOP_PARAMETER_TYPE(std::string)
SERVOLOOP_PARAMETER_TYPE(std::vector<double>)
SERVOLOOP_PARAMETER_TYPE(std::vector<int>)
SERVOLOOP_PARAMETER_TYPE(std::vector<std::string>)
#undef SERVOLOOP_PARAMETER_TYPE

// --- writing -------------------------------------------------------------------

void ParameterStore::insertLocked(const std::string& absolute_name, const YAML::Node& value,
                                  const std::string& source) {
  const std::vector<std::string> segments = splitName(absolute_name);
  if (segments.empty()) {
    throw Error("cannot replace the root namespace '/' with a single value; set a name under it");
  }
  // Forget where the replaced subtree came from.
  const std::string prefix = absolute_name + "/";
  for (auto it = sources_.lower_bound(absolute_name);
       it != sources_.end() && (it->first == absolute_name || it->first.starts_with(prefix));) {
    it = sources_.erase(it);
  }
  // Walk down, turning anything in the way that is not a map into one, as rosparam does.
  YAML::Node current;
  current.reset(root_);
  std::string walked;
  for (std::size_t i = 0; i + 1 < segments.size(); ++i) {
    walked += "/" + segments[i];
    const YAML::Node child = childOf(current, segments[i]);  // invalid (not resettable) if missing
    if (child.IsDefined() && child.IsMap()) {
      current.reset(child);
      continue;
    }
    current[segments[i]] = YAML::Node(YAML::NodeType::Map);
    sources_.erase(walked);
    const YAML::Node created = childOf(current, segments[i]);
    current.reset(created);
  }
  current[segments.back()] = value;
  sources_[absolute_name] = source;
}

void ParameterStore::set(std::string_view name, std::string_view yaml_value) {
  checkParameterName(name);
  YAML::Node value;
  try {
    value = YAML::Load(std::string(yaml_value));
  } catch (const YAML::Exception& e) {
    throw Error("parameter '" + resolveName("/", name) + "': value '" + std::string(yaml_value) +
                "' is not valid YAML (" + e.msg + "); quote it or fix the brackets");
  }
  checkYamlDocument(value, "parameter '" + resolveName("/", name) + "'");
  setNode(name, value);
}

void ParameterStore::set(std::string_view name, double value) {
  std::lock_guard lock(mutex_);
  insertLocked(settableName(name), YAML::Node(formatDouble(value)), std::string(kSetSource));
}

void ParameterStore::set(std::string_view name, int value) { set(name, static_cast<std::int64_t>(value)); }

void ParameterStore::set(std::string_view name, std::int64_t value) {
  std::lock_guard lock(mutex_);
  insertLocked(settableName(name), YAML::Node(std::to_string(value)), std::string(kSetSource));
}

void ParameterStore::set(std::string_view name, bool value) {
  std::lock_guard lock(mutex_);
  insertLocked(settableName(name), YAML::Node(value ? "true" : "false"), std::string(kSetSource));
}

void ParameterStore::set(std::string_view name, const std::vector<double>& value) {
  YAML::Node list(YAML::NodeType::Sequence);
  for (double item : value) list.push_back(YAML::Node(formatDouble(item)));
  std::lock_guard lock(mutex_);
  insertLocked(settableName(name), list, std::string(kSetSource));
}

void ParameterStore::set(std::string_view name, const std::vector<std::string>& value) {
  YAML::Node list(YAML::NodeType::Sequence);
  for (const std::string& item : value) {
    YAML::Node text(item);
    text.SetTag("!");
    list.push_back(text);
  }
  std::lock_guard lock(mutex_);
  insertLocked(settableName(name), list, std::string(kSetSource));
}

void ParameterStore::setString(std::string_view name, std::string_view value) {
  YAML::Node text{std::string(value)};
  text.SetTag("!");
  std::lock_guard lock(mutex_);
  insertLocked(settableName(name), text, std::string(kSetSource));
}

void ParameterStore::setNode(std::string_view name, const YAML::Node& value) {
  const std::string absolute_name = settableName(name);
  if (absolute_name == "/" && !value.IsMap()) {
    throw Error("cannot replace the root namespace '/' with a " +
                std::string(paramTypeName(paramTypeOf(value))) + "; set a name under it");
  }
  // Every key is checked before anything changes: a refused value leaves
  // the store as it was (set replaces, so a late refusal would have removed
  // the old value already).
  std::vector<std::pair<std::string, YAML::Node>> pending{{absolute_name, value}};
  while (!pending.empty()) {
    const auto [target, node] = pending.back();
    pending.pop_back();
    if (!node.IsMap()) continue;
    for (const auto& entry : node) {
      if (!entry.first.IsScalar() || entry.first.Scalar().empty()) {
        throw Error("parameter '" + target + "': a key must be a plain name, not a list, a map or empty");
      }
      if (entry.first.Scalar().front() == '~') {
        throw Error("parameter '" + target + "': key '" + entry.first.Scalar() +
                    "' is a private '~' name, which has no meaning in the parameter store; give the plain key");
      }
      pending.emplace_back(joinName(target, entry.first.Scalar()), entry.second);
    }
  }
  // Going through the loader normalises nested keys ("a/b") and records sources.
  YAML::Node wrapper(YAML::NodeType::Map);
  std::lock_guard lock(mutex_);
  if (absolute_name != "/") {
    // Replace rather than merge: `rosparam set` overwrites the whole value.
    const std::vector<std::string> segments = splitName(absolute_name);
    YAML::Node parent = findLocked(parentOf(absolute_name));
    if (parent.IsMap() && childOf(parent, segments.back()).IsDefined()) parent.remove(segments.back());
  }
  struct Copier {
    ParameterStore& store;
    void copy(const std::string& target, const YAML::Node& node) {
      if (!node.IsMap()) {
        store.insertLocked(target, YAML::Clone(node), std::string(kSetSource));
        return;
      }
      if (target != "/") store.insertLocked(target, YAML::Node(YAML::NodeType::Map), std::string(kSetSource));
      for (const auto& entry : node) {
        copy(joinName(target, entry.first.Scalar()), entry.second);
      }
    }
  };
  Copier{*this}.copy(absolute_name, value);
}

bool ParameterStore::remove(std::string_view name) {
  const std::string absolute_name = resolveName("/", name);
  std::lock_guard lock(mutex_);
  if (absolute_name == "/") {
    const bool had_any = root_.size() > 0;
    root_.reset(YAML::Node(YAML::NodeType::Map));
    sources_.clear();
    return had_any;
  }
  YAML::Node parent = findLocked(parentOf(absolute_name));
  const std::string key = splitName(absolute_name).back();
  if (!parent.IsMap() || !childOf(parent, key).IsDefined()) return false;
  parent.remove(key);
  const std::string prefix = absolute_name + "/";
  for (auto it = sources_.lower_bound(absolute_name);
       it != sources_.end() && (it->first == absolute_name || it->first.starts_with(prefix));) {
    it = sources_.erase(it);
  }
  return true;
}

// --- reading whole subtrees ----------------------------------------------------------

bool ParameterStore::has(std::string_view name) const {
  const std::string absolute_name = resolveName("/", name);
  std::lock_guard lock(mutex_);
  return hasLocked(absolute_name);
}

YAML::Node ParameterStore::node(std::string_view name) const {
  const std::string absolute_name = resolveName("/", name);
  std::lock_guard lock(mutex_);
  return YAML::Clone(requireLocked(absolute_name));
}

std::string ParameterStore::dump(std::string_view ns) const {
  const std::string absolute_name = resolveName("/", ns);
  std::lock_guard lock(mutex_);
  const YAML::Node value = requireLocked(absolute_name);
  YAML::Emitter out;
  emitValue(out, value);
  return std::string(out.c_str()) + "\n";
}

std::vector<std::string> ParameterStore::list(std::string_view ns) const {
  const std::string absolute_name = resolveName("/", ns);
  std::lock_guard lock(mutex_);
  const YAML::Node value = findLocked(absolute_name);
  std::vector<std::string> names;
  if (!value.IsDefined()) return names;
  if (absolute_name == "/" && value.size() == 0) return names;
  collectLeaves(value, absolute_name, names);
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<std::string> ParameterStore::childNames(std::string_view ns) const {
  const std::string absolute_name = resolveName("/", ns);
  std::lock_guard lock(mutex_);
  const YAML::Node value = findLocked(absolute_name);
  std::vector<std::string> names;
  if (!value.IsMap()) return names;
  for (const auto& entry : value) names.push_back(entry.first.Scalar());
  std::sort(names.begin(), names.end());
  return names;
}

std::string ParameterStore::sourceOf(std::string_view name) const {
  const std::string absolute_name = resolveName("/", name);
  std::lock_guard lock(mutex_);
  if (!hasLocked(absolute_name)) return "";
  return sourceLocked(absolute_name);
}

}  // namespace servoloop::params
