#pragma once
// The message of the exception `fn` throws, checked to be of type E (by
// default servoloop::Error or a subclass); a test failure, and "", when it
// throws nothing.
#include <string>

#include <gtest/gtest.h>

#include "servoloop/core/errors.hpp"

namespace servoloop::testing {

template <class E = servoloop::Error, class Fn>
std::string thrownMessage(Fn&& fn) {
  try {
    fn();
  } catch (const E& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an exception, none was thrown";
  return "";
}

}  // namespace servoloop::testing
