#pragma once
// A controller's (or a backend's) parameters: a read-only view of one subtree
// of the parameter store, e.g. everything under
// /one_DOF_robot/joint1_position_controller, with typed reads whose errors
// name the full parameter path. This is the one way servoloop code reads
// parameters; yaml-cpp stays out of this header (parameters_yaml.hpp has the
// bridge for code that builds views from YAML).
//
// Non-real-time: read parameters in init/configure, never on the control cycle.
//
//   const auto& p = context.params;
//   joint_ = hw->getHandle(p.get<std::string>("joint"));   // required
//   gain_ = p.get<double>("gain", 10.0);                    // optional, default 10
//   for (const auto& name : p.get<std::vector<std::string>>("joints")) ...
//   const params::Parameters gains = p.child("pid");         // nested: also p.child("pid/p")
//
// Supported types: bool, int, double (finite), std::string, and std::vector of
// double or std::string. A missing required value, a value of the wrong type
// or a non-finite number throws servoloop::ConfigError, e.g.
//   parameter '/one_DOF_robot/ctrl/pid/p' must be a finite number, got 'abc'
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace servoloop::params {

class Parameters {
 public:
  // No parameters at all: every key is missing.
  Parameters();

  // The ROS name of this subtree, e.g. "/one_DOF_robot/joint1_position_controller".
  const std::string& path() const noexcept { return path_; }
  // path() + "/" + key.
  std::string pathOf(std::string_view key) const;

  // Nothing here (a missing key or an explicit null).
  bool empty() const noexcept;
  // Something here (as a yaml-cpp node tests): `if (params["output"]) ...`.
  explicit operator bool() const noexcept { return !empty(); }
  bool isMap() const noexcept;
  bool isList() const noexcept;
  bool isScalar() const noexcept;

  // Whether key (nested with '/', e.g. "pid/p") holds a non-null value.
  bool has(std::string_view key) const;
  // The subtree at key; an empty view (whose path still names it) when missing.
  Parameters child(std::string_view key) const;
  Parameters operator[](std::string_view key) const { return child(key); }
  // The keys of a map, in file order; none otherwise.
  std::vector<std::string> keys() const;
  // The length of a list (0 otherwise) and its items, named path[i].
  std::size_t size() const noexcept;
  Parameters item(std::size_t index) const;

  // This value as T; throws servoloop::ConfigError naming path() when it is
  // missing or not a T.
  template <class T>
  T as() const;
  // The value at key as T (required).
  template <class T>
  T get(std::string_view key) const {
    return child(key).template as<T>();
  }
  // The value at key as T, or fallback when the key is missing or null.
  template <class T>
  T get(std::string_view key, const T& fallback) const {
    const Parameters value = child(key);
    return value.empty() ? fallback : value.template as<T>();
  }

  // How the value reads in a message: 'text' for a scalar, "a list", "a map"
  // or "nothing".
  std::string describe() const;

  struct Impl;  // parameters.cpp (a yaml-cpp node)

 private:
  friend class ParametersAccess;
  Parameters(std::shared_ptr<const Impl> impl, std::string path);

  std::shared_ptr<const Impl> impl_;
  std::string path_;
};

template <>
bool Parameters::as<bool>() const;
template <>
int Parameters::as<int>() const;
template <>
double Parameters::as<double>() const;
template <>
std::string Parameters::as<std::string>() const;
template <>
std::vector<double> Parameters::as<std::vector<double>>() const;
template <>
std::vector<std::string> Parameters::as<std::vector<std::string>>() const;

// Reads map[key] into out when it is there; false (out untouched) when the key
// is missing or null. A value of another type throws servoloop::ConfigError
// "<where>/<key>: expected a number, got 'abc'" (where names the map as the
// user wrote it, e.g. "joint_limits/joint1"). For bool, int and double.
template <class T>
bool readOptional(const Parameters& map, std::string_view key, const std::string& where, T& out);

}  // namespace servoloop::params
