#pragma once
// Index types that cannot be mixed: a JointIndex is not an ActuatorIndex.
#include <compare>
#include <cstddef>

namespace servoloop {

template <class Tag>
class StrongIndex {
 public:
  constexpr StrongIndex() = default;
  constexpr explicit StrongIndex(std::size_t value) : value_(value) {}
  constexpr std::size_t value() const { return value_; }
  constexpr auto operator<=>(const StrongIndex&) const = default;

 private:
  std::size_t value_ = 0;
};

using JointIndex = StrongIndex<struct JointIndexTag>;
using ActuatorIndex = StrongIndex<struct ActuatorIndexTag>;

}  // namespace servoloop
