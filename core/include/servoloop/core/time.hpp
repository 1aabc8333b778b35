#pragma once
// Control time, in seconds. Simulated time in simulation, monotonic wall time
// on real hardware; kept as strong types so a time point and a period are never
// mixed up.
#include <compare>

namespace servoloop {

// The physics time steps servoloop accepts, in seconds: below a microsecond a
// run makes no progress anyone can wait for; above a second it simulates
// nothing a controller could act on.
inline constexpr double kMinTimeStepS = 1e-6;
inline constexpr double kMaxTimeStepS = 1.0;

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
