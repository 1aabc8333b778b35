#include "servoloop/controllers/common/angles.hpp"

#include <cmath>
#include <numbers>

namespace servoloop::controllers {

namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;
}  // namespace

double wrapToPi(double angle_rad) noexcept {
  if (!std::isfinite(angle_rad)) return angle_rad;
  // ceil puts odd multiples of π on +π, so the result is in (-π, π].
  return angle_rad - kTwoPi * std::ceil((angle_rad - std::numbers::pi) / kTwoPi);
}

double shortestAngularDistance(double from_rad, double to_rad) noexcept {
  return wrapToPi(to_rad - from_rad);
}

double shortestAngularDistanceWithinLimits(double from_rad, double to_rad, double lower_rad,
                                           double upper_rad) noexcept {
  const double direct = to_rad - from_rad;
  if (!std::isfinite(direct)) return direct;
  // Candidate end points are to_rad + 2πk; only those inside the limits count.
  // k is bounded by the width of the range, so a few turns cover every case.
  const double first_k = std::ceil((lower_rad - to_rad) / kTwoPi);
  const double last_k = std::floor((upper_rad - to_rad) / kTwoPi);
  if (!(first_k <= last_k) || !std::isfinite(first_k) || !std::isfinite(last_k)) return direct;
  // The candidate nearest to from_rad: k* = round((from - to)/2π), clamped to
  // the allowed turns.
  double best_k = std::round((from_rad - to_rad) / kTwoPi);
  if (best_k < first_k) best_k = first_k;
  if (best_k > last_k) best_k = last_k;
  return direct + kTwoPi * best_k;
}

}  // namespace servoloop::controllers
