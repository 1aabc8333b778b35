#pragma once
// The parameter server of a servoloop node: a tree of named values loaded from
// ros_control YAML files as they are, addressed with ROS-style names such as
// /one_DOF_robot/joint1_position_controller/pid/p.
//
// Non-real-time only: every call takes a mutex and may allocate. Controllers
// read their parameters during init (usually from the YAML::Node subtree that
// node() returns), never from update().
//
// Typing follows YAML as rosparam reads it: 10 is an int, 10.0 a double,
// true/yes/on a bool, "10" (quoted) a string. An int is accepted where a
// double is asked for (as ROS does); nothing else converts.
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "servoloop/core/errors.hpp"

namespace servoloop::params {

// A name that is not in the store.
class ParameterNotFoundError : public Error {
 public:
  using Error::Error;
};

// A value that exists but is not of the type asked for.
class ParameterTypeError : public Error {
 public:
  using Error::Error;
};

enum class ParamType { null, boolean, integer, floating, string, list, map };

// "null", "bool", "int", "double", "string", "list", "map".
std::string_view paramTypeName(ParamType type);

// The type of a YAML node under the rules above (plain scalars resolved by
// their text, quoted or !!str scalars are strings).
ParamType paramTypeOf(const YAML::Node& node);

// The value of a scalar whose paramTypeOf is integer (paramIntegerValue) or
// integer/floating (paramDoubleValue); servoloop::Error for anything else.
std::int64_t paramIntegerValue(const YAML::Node& scalar);
double paramDoubleValue(const YAML::Node& scalar);

// Resolves a name against a namespace the ROS way: "/a/b" is absolute,
// "b" in namespace "/a" is "/a/b". The result is normalised: one leading '/',
// no empty segments, no trailing '/' ("/" is the root). '~' names are not
// supported and throw servoloop::Error.
std::string resolveName(std::string_view ns, std::string_view name);

// The longest parameter name a setter takes (names are paths of a few keys).
inline constexpr std::size_t kMaxParameterNameLength = 1024;

// Throws servoloop::Error naming `name` and the rule unless it is a name every
// setter (set, setString, setNode) and a load's namespace take: a ROS graph
// resource name (first character a letter or '/', then letters, digits, '_'
// and '/'), not empty (that would be the whole namespace) and not a private
// '~' name (which has no meaning outside a ROS node). Reads are not checked.
void checkParameterName(std::string_view name);

// The most nodes a YAML document may hold with its aliases expanded: anchors
// and aliases let a few lines stand for billions of nodes, and every reader
// that walks the document (dump, JSON, a controller's list) would expand them.
inline constexpr std::size_t kMaxYamlNodes = 1'000'000;

// Throws ConfigError naming `source_name` when `document`, aliases expanded,
// holds more than kMaxYamlNodes nodes (counting stops at the limit), or when a
// map holds the same key twice (ROS's YAML reader keeps the last, yaml-cpp
// the first: either silently gives a value the user did not mean).
void checkYamlDocument(const YAML::Node& document, std::string_view source_name);

// The node count of checkYamlDocument alone, for readers that take a key
// given twice as Python's YAML reader does (the last one wins): xacro's
// load_yaml.
void checkYamlSize(const YAML::Node& document, std::string_view source_name);

class ParameterStore {
 public:
  ParameterStore();
  ParameterStore(const ParameterStore&) = delete;
  ParameterStore& operator=(const ParameterStore&) = delete;

  // Loads a YAML file (top level: a map, or empty) under namespace ns, merging
  // maps into what is already there and replacing everything else, as
  // `rosparam load` does. Keys containing '/' nest. Errors (servoloop::ConfigError)
  // name the file, the line:column and the fix.
  void loadFile(const std::string& path, std::string_view ns = "/");
  // The same for YAML text; source_name stands for the file name in errors.
  void loadString(std::string_view yaml, std::string_view source_name, std::string_view ns = "/");

  // Relative names resolve against "/".
  bool has(std::string_view name) const;

  // Typed read. Supported T: double, int, std::int64_t, bool, std::string,
  // std::vector<double>, std::vector<int>, std::vector<std::string>.
  // Throws ParameterNotFoundError (naming what the parent namespace has) or
  // ParameterTypeError (naming the key, the expected and the actual type, and
  // the file:line the value came from).
  template <class T>
  T get(std::string_view name) const;

  // Typed read with a default for a missing name. A present value of the wrong
  // type still throws: a typo in a YAML value should not silently become a default.
  template <class T>
  T get(std::string_view name, const T& default_value) const {
    T value;
    return tryGet(name, value) ? value : default_value;
  }
  std::string get(std::string_view name, const char* default_value) const {
    return get<std::string>(name, std::string(default_value));
  }

  // Typed read into out; false (out untouched) when the name is missing.
  template <class T>
  bool tryGet(std::string_view name, T& out) const;

  // Sets a value from text typed like YAML / `rosparam set`: "1.0" → double,
  // "1" → int, "true" → bool, "[1, 2]" → list, "{p: 1}" → map, "abc" → string.
  void set(std::string_view name, std::string_view yaml_value);
  void set(std::string_view name, const char* yaml_value) { set(name, std::string_view(yaml_value)); }
  // Typed setters: the value keeps exactly this type.
  void set(std::string_view name, double value);
  void set(std::string_view name, int value);
  void set(std::string_view name, std::int64_t value);
  void set(std::string_view name, bool value);
  void set(std::string_view name, const std::vector<double>& value);
  void set(std::string_view name, const std::vector<std::string>& value);
  // A string value taken literally (never parsed as YAML).
  void setString(std::string_view name, std::string_view value);
  // A whole subtree (copied).
  void setNode(std::string_view name, const YAML::Node& value);

  // Removes a name and everything under it; false if it was not there.
  bool remove(std::string_view name);

  // A deep copy of the value or subtree at name (a controller's parameters,
  // e.g. node("/one_DOF_robot/joint1_position_controller")). Throws
  // ParameterNotFoundError if missing.
  YAML::Node node(std::string_view name) const;

  // The subtree at ns as YAML text that loadString() reads back to the same
  // values and types. Throws ParameterNotFoundError for a missing ns.
  std::string dump(std::string_view ns = "/") const;

  // Full names of every value under ns (leaves: scalars, lists, empty maps),
  // sorted, like `rosparam list`. Empty for a missing ns.
  std::vector<std::string> list(std::string_view ns = "/") const;

  // The keys directly under ns (e.g. the controller names of a robot
  // namespace), sorted. Empty if ns is missing or not a map.
  std::vector<std::string> childNames(std::string_view ns = "/") const;

  // Where the value at name came from: "file.yaml:7:5", "set", or "" if unknown.
  std::string sourceOf(std::string_view name) const;

 private:
  // All private members expect mutex_ held.
  // Undefined node when missing.
  YAML::Node findLocked(const std::string& absolute_name) const;
  bool hasLocked(const std::string& absolute_name) const;
  YAML::Node requireLocked(const std::string& absolute_name) const;
  void insertLocked(const std::string& absolute_name, const YAML::Node& value, const std::string& source);
  [[noreturn]] void throwTypeError(const std::string& absolute_name, const YAML::Node& value,
                                   std::string_view expected) const;
  std::string sourceLocked(const std::string& absolute_name) const;
  template <class T>
  T convertLocked(const std::string& absolute_name, const YAML::Node& value) const;

  mutable std::mutex mutex_;
  YAML::Node root_;  // always a map with string keys; maps nested likewise
  // Full name → "file:line:col" for every value inserted from a file, "set" for set().
  std::map<std::string, std::string> sources_;
};

}  // namespace servoloop::params
