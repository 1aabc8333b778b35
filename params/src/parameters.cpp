#include "servoloop/params/parameters.hpp"

#include <cmath>
#include <type_traits>
#include <utility>

#include "servoloop/core/errors.hpp"
#include "servoloop/params/parameters_yaml.hpp"

namespace servoloop::params {

struct Parameters::Impl {
  YAML::Node node;  // never modified once the view exists
};

// Builds views; the only code that sees Parameters' representation.
class ParametersAccess {
 public:
  static Parameters make(YAML::Node node, std::string path) {
    return Parameters(std::make_shared<const Parameters::Impl>(Parameters::Impl{std::move(node)}),
                      std::move(path));
  }
  static const YAML::Node* node(const Parameters& parameters) {
    return parameters.impl_ ? &parameters.impl_->node : nullptr;
  }
};

namespace {

const YAML::Node* nodeOf(const Parameters& parameters) { return ParametersAccess::node(parameters); }

bool present(const YAML::Node* node) { return node != nullptr && node->IsDefined() && !node->IsNull(); }

[[noreturn]] void throwWrongType(const Parameters& value, const char* expected) {
  if (value.empty()) throw ConfigError("parameter '" + value.path() + "' is missing");
  throw ConfigError("parameter '" + value.path() + "' must be " + expected + ", got " + value.describe());
}

// The scalar text of value, or a ConfigError naming what was expected.
std::string scalarOf(const Parameters& value, const char* expected) {
  const YAML::Node* node = nodeOf(value);
  if (!present(node) || !node->IsScalar()) throwWrongType(value, expected);
  return node->Scalar();
}

template <class T>
T convert(const Parameters& value, const char* expected) {
  scalarOf(value, expected);
  try {
    return nodeOf(value)->as<T>();
  } catch (const YAML::Exception&) {
    throwWrongType(value, expected);
  }
}

template <class T>
std::vector<T> listOf(const Parameters& value, const char* expected) {
  if (!value.isList()) throwWrongType(value, expected);
  std::vector<T> items;
  items.reserve(value.size());
  for (std::size_t i = 0; i < value.size(); ++i) items.push_back(value.item(i).template as<T>());
  return items;
}

}  // namespace

Parameters::Parameters() = default;

Parameters::Parameters(std::shared_ptr<const Impl> impl, std::string path)
    : impl_(std::move(impl)), path_(std::move(path)) {}

std::string Parameters::pathOf(std::string_view key) const {
  if (path_.empty() || path_ == "/") return "/" + std::string(key);
  return path_ + "/" + std::string(key);
}

bool Parameters::empty() const noexcept { return !present(nodeOf(*this)); }
bool Parameters::isMap() const noexcept { return present(nodeOf(*this)) && nodeOf(*this)->IsMap(); }
bool Parameters::isList() const noexcept { return present(nodeOf(*this)) && nodeOf(*this)->IsSequence(); }
bool Parameters::isScalar() const noexcept { return present(nodeOf(*this)) && nodeOf(*this)->IsScalar(); }

bool Parameters::has(std::string_view key) const { return !child(key).empty(); }

Parameters Parameters::child(std::string_view key) const {
  // reset(), never operator=: assigning to a yaml-cpp node writes into the tree it refers to.
  YAML::Node current(YAML::NodeType::Undefined);
  if (present(nodeOf(*this))) current.reset(*nodeOf(*this));
  std::size_t start = 0;
  while (start <= key.size()) {
    std::size_t end = key.find('/', start);
    if (end == std::string_view::npos) end = key.size();
    const std::string part(key.substr(start, end - start));
    if (!part.empty()) {
      YAML::Node next(YAML::NodeType::Undefined);
      if (current.IsDefined() && current.IsMap()) {
        const YAML::Node& map = current;  // const lookup: never inserts the key
        const YAML::Node found = map[part];
        if (found.IsDefined()) next.reset(found);
      }
      current.reset(next);
    }
    start = end + 1;
  }
  return ParametersAccess::make(current, pathOf(key));
}

std::vector<std::string> Parameters::keys() const {
  std::vector<std::string> names;
  if (!isMap()) return names;
  for (const auto& entry : *nodeOf(*this)) names.push_back(entry.first.Scalar());
  return names;
}

std::size_t Parameters::size() const noexcept { return isList() ? nodeOf(*this)->size() : 0; }

Parameters Parameters::item(std::size_t index) const {
  const std::string item_path = path_ + "[" + std::to_string(index) + "]";
  if (index >= size()) return ParametersAccess::make(YAML::Node(YAML::NodeType::Undefined), item_path);
  const YAML::Node& list = *nodeOf(*this);
  return ParametersAccess::make(list[index], item_path);
}

std::string Parameters::describe() const {
  const YAML::Node* node = nodeOf(*this);
  if (!present(node)) return "nothing";
  if (node->IsScalar()) return "'" + node->Scalar() + "'";
  if (node->IsSequence()) return "a list";
  return "a map";
}

template <>
bool Parameters::as<bool>() const {
  return convert<bool>(*this, "a boolean (true or false)");
}

template <>
int Parameters::as<int>() const {
  return convert<int>(*this, "an integer");
}

template <>
double Parameters::as<double>() const {
  const double value = convert<double>(*this, "a finite number");
  if (!std::isfinite(value)) throwWrongType(*this, "a finite number");
  return value;
}

template <>
std::string Parameters::as<std::string>() const {
  return scalarOf(*this, "a string");
}

template <>
std::vector<double> Parameters::as<std::vector<double>>() const {
  return listOf<double>(*this, "a list of numbers");
}

template <>
std::vector<std::string> Parameters::as<std::vector<std::string>>() const {
  return listOf<std::string>(*this, "a list of strings");
}

template <class T>
bool readOptional(const Parameters& map, std::string_view key, const std::string& where, T& out) {
  const Parameters value = map.child(key);
  if (value.empty()) return false;
  const char* expected = std::is_same_v<T, bool>  ? "a boolean (true or false)"
                         : std::is_same_v<T, int> ? "an integer"
                                                  : "a number";
  const auto fail = [&] {
    return ConfigError(where + "/" + std::string(key) + ": expected " + expected + ", got " + value.describe());
  };
  if (!value.isScalar()) throw fail();
  try {
    out = value.as<T>();
  } catch (const ConfigError&) {
    throw fail();
  }
  return true;
}

template bool readOptional<bool>(const Parameters&, std::string_view, const std::string&, bool&);
template bool readOptional<int>(const Parameters&, std::string_view, const std::string&, int&);
template bool readOptional<double>(const Parameters&, std::string_view, const std::string&, double&);

Parameters parametersFromYaml(const YAML::Node& node, std::string path) {
  return ParametersAccess::make(node.IsDefined() ? YAML::Clone(node) : YAML::Node(YAML::NodeType::Undefined),
                                std::move(path));
}

YAML::Node toYaml(const Parameters& parameters) {
  const YAML::Node* node = nodeOf(parameters);
  return node != nullptr && node->IsDefined() ? YAML::Clone(*node) : YAML::Node(YAML::NodeType::Undefined);
}

}  // namespace servoloop::params
