#pragma once
// Numbers as text for people and files (topic echo, CSV, parameter dumps).
#include <string>

namespace servoloop {

// Shortest text that reads back as the same double, always with a decimal
// point or exponent ("1.0", "0.1", "1e-07"); "nan", "inf", "-inf".
std::string formatDouble(double value);

}  // namespace servoloop
