#pragma once
// Control time, in seconds. Simulated time in simulation, monotonic wall time
// on real hardware; kept as strong types so a time point and a period are never
// mixed up.
#include <compare>

namespace servoloop {

struct Duration {
  double seconds = 0.0;

  constexpr Duration() = default;
  constexpr explicit Duration(double s) : seconds(s) {}
  constexpr Duration operator+(Duration o) const { return Duration(seconds + o.seconds); }
  constexpr Duration operator-(Duration o) const { return Duration(seconds - o.seconds); }
  constexpr Duration operator*(double k) const { return Duration(seconds * k); }
  constexpr Duration& operator+=(Duration o) { seconds += o.seconds; return *this; }
  constexpr auto operator<=>(const Duration&) const = default;
};

struct Time {
  double seconds = 0.0;

  constexpr Time() = default;
  constexpr explicit Time(double s) : seconds(s) {}
  constexpr Time operator+(Duration d) const { return Time(seconds + d.seconds); }
  constexpr Time operator-(Duration d) const { return Time(seconds - d.seconds); }
  constexpr Duration operator-(Time o) const { return Duration(seconds - o.seconds); }
  constexpr Time& operator+=(Duration d) { seconds += d.seconds; return *this; }
  constexpr auto operator<=>(const Time&) const = default;
};

}  // namespace servoloop
