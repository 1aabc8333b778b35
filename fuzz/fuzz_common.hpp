#pragma once
// What every fuzz target shares: the input as text, and the rule that a
// servoloop::Error (a refusal naming the input) is the expected answer to bad
// input, while any other exception, a crash, a hang or a sanitizer report is
// a bug the fuzzer reports.
#include <cstddef>
#include <cstdint>
#include <string>

#include "servoloop/core/errors.hpp"

namespace servoloop::fuzz {

inline std::string text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

template <class Work>
int refusalsAllowed(Work&& work) {
  try {
    work();
  } catch (const servoloop::Error&) {
    // A clear refusal: what bad input must get.
  }
  return 0;
}

}  // namespace servoloop::fuzz
