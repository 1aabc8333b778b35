#pragma once
// Compares a xacro expansion with the URDF a person expanded by hand: both are
// reduced to a canonical text (elements and attributes in order, whitespace
// and comments dropped, numbers compared by value to 1e-12 relative).
#include <string>

namespace servoloop::testing {

// Canonical one-line form of `xml`; numbers in attributes and text are
// printed with 12 significant digits.
std::string canonicalXml(const std::string& xml);

}  // namespace servoloop::testing
