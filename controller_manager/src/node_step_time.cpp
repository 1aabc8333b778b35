// Simulated time on the physics step grid (step_time.hpp).
#include "servoloop/controller_manager/node/step_time.hpp"

#include <cmath>

namespace servoloop::controller_manager::node {
namespace {

// Every integer up to 2^53 is a double; products below it are exact.
constexpr double kExactIntegerLimit = 9007199254740992.0;

// 10^k for k = 0..15, each exactly representable.
constexpr double kPowersOfTen[] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                   1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};

}  // namespace

double stepsToSeconds(std::uint64_t steps, double step_s) noexcept {
  const double step_count = static_cast<double>(steps);
  if (!(step_s > 0.0) || !std::isfinite(step_s)) return step_count * step_s;
  // The shortest decimal m / 10^k that reads back as step_s.
  for (const double power : kPowersOfTen) {
    const double mantissa = std::nearbyint(step_s * power);
    if (mantissa < 1.0 || mantissa > kExactIntegerLimit) continue;
    if (mantissa / power != step_s) continue;
    if (step_count > kExactIntegerLimit / mantissa) break;  // steps · m would be rounded
    return step_count * mantissa / power;                   // exact product, one rounding
  }
  return step_count * step_s;
}

double snapToStepGrid(double time_s, double step_s) noexcept {
  if (!(step_s > 0.0) || !std::isfinite(step_s) || !(time_s >= 0.0) || !std::isfinite(time_s)) return time_s;
  const double steps = std::nearbyint(time_s / step_s);
  if (steps > kExactIntegerLimit) return time_s;
  if (std::abs(steps * step_s - time_s) > 1e-6 * step_s) return time_s;
  return stepsToSeconds(static_cast<std::uint64_t>(steps), step_s);
}

}  // namespace servoloop::controller_manager::node
