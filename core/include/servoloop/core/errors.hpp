#pragma once
// Errors thrown for bad user input or misuse outside the real-time path.
// Messages name the file/element/handle at fault and say what to do.
#include <stdexcept>
#include <string>

namespace servoloop {

// Base of every error servoloop throws for input the user can fix.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A handle name an interface does not know.
class UnknownHandleError : public Error {
 public:
  using Error::Error;
};

// A configuration file (URDF, YAML, launch file) that cannot be used as written.
class ConfigError : public Error {
 public:
  using Error::Error;
};

}  // namespace servoloop
