// Simulated time on the physics step grid (step_grid.hpp).
#include "servoloop/core/step_grid.hpp"

#include <cmath>

namespace servoloop {
namespace {

// 10^k for k = 0..15, each exactly representable.
constexpr double kPowersOfTen[] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                   1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};

}  // namespace

StepGrid::StepGrid(double step_s) noexcept : step_s_(step_s) {
  if (!(step_s > 0.0) || !std::isfinite(step_s)) return;
  if (std::isfinite(1.0 / step_s)) {  // a subnormal step: no snapping
    inverse_step_ = 1.0 / step_s;
    max_snap_time_s_ = kExactIntegerLimit * step_s;
    snap_tolerance_s_ = 1e-6 * step_s;
  }
  // The shortest decimal m / 10^k that reads back as step_s.
  for (const double power : kPowersOfTen) {
    const double mantissa = std::nearbyint(step_s * power);
    if (mantissa < 1.0 || mantissa > kExactIntegerLimit) continue;
    if (mantissa / power != step_s) continue;
    mantissa_ = mantissa;
    power_ = power;
    // steps · m is exact while it stays at or below 2^53.
    max_exact_steps_ = static_cast<std::uint64_t>(std::floor(kExactIntegerLimit / mantissa));
    return;
  }
}

}  // namespace servoloop
