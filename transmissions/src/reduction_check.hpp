#pragma once
// Construction-time checks shared by the transmission classes (not real-time).
#include <cmath>
#include <string>

#include "servoloop/core/errors.hpp"

namespace servoloop::transmissions::detail {

// A reduction divides in one direction of every map, so zero (or NaN/inf)
// would make the transmission meaningless.
inline void requireUsableReduction(const char* transmission, const std::string& which,
                                   double value) {
  if (value == 0.0 || !std::isfinite(value)) {
    throw ConfigError(std::string(transmission) + ": " + which + " is " + std::to_string(value) +
                      "; a mechanical reduction must be a non-zero finite number "
                      "(1 for a direct drive, negative to reverse the direction)");
  }
}

inline void requireFiniteOffset(const char* transmission, const std::string& which, double value) {
  if (!std::isfinite(value)) {
    throw ConfigError(std::string(transmission) + ": " + which + " is " + std::to_string(value) +
                      "; a joint offset must be a finite number (rad or m)");
  }
}

}  // namespace servoloop::transmissions::detail
