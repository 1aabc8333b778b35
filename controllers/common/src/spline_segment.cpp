#include "servoloop/controllers/common/spline_segment.hpp"

#include <cmath>
#include <initializer_list>

namespace servoloop::controllers {

SplineSegment::SplineSegment(double start_time, const JointSample& start, double end_time, const JointSample& end,
                             SplineKind kind) noexcept
    : start_time_(start_time), duration_(end_time > start_time ? end_time - start_time : 0.0), kind_(kind) {
  auto& c = coefficients_;
  if (duration_ == 0.0) {
    // Nothing to interpolate: the segment is its end point.
    c[0] = end.position;
    if (kind != SplineKind::linear) c[1] = end.velocity;
    if (kind == SplineKind::quintic) c[2] = 0.5 * end.acceleration;
    return;
  }
  const double T = duration_;
  const double p0 = start.position;
  const double p1 = end.position;
  c[0] = p0;
  if (kind == SplineKind::linear) {
    c[1] = (p1 - p0) / T;
    return;
  }
  const double v0 = start.velocity;
  const double v1 = end.velocity;
  c[1] = v0;
  if (kind == SplineKind::cubic) {
    // p(T) = p1 and p'(T) = v1 solved for c2 and c3.
    c[2] = (3.0 * (p1 - p0) - (2.0 * v0 + v1) * T) / (T * T);
    c[3] = (2.0 * (p0 - p1) + (v0 + v1) * T) / (T * T * T);
    return;
  }
  const double a0 = start.acceleration;
  const double a1 = end.acceleration;
  c[2] = 0.5 * a0;
  // p(T) = p1, p'(T) = v1 and p''(T) = a1 solved for c3, c4 and c5.
  const double T2 = T * T;
  c[3] = (20.0 * (p1 - p0) - (8.0 * v1 + 12.0 * v0) * T - (3.0 * a0 - a1) * T2) / (2.0 * T2 * T);
  c[4] = (30.0 * (p0 - p1) + (14.0 * v1 + 16.0 * v0) * T + (3.0 * a0 - 2.0 * a1) * T2) / (2.0 * T2 * T2);
  c[5] = (12.0 * (p1 - p0) - 6.0 * (v1 + v0) * T - (a0 - a1) * T2) / (2.0 * T2 * T2 * T);
}

JointSample SplineSegment::evaluate(double t) const noexcept {
  const auto& c = coefficients_;
  // Horner's scheme for the polynomial and its two derivatives.
  JointSample s;
  s.position = c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5]))));
  s.velocity = c[1] + t * (2.0 * c[2] + t * (3.0 * c[3] + t * (4.0 * c[4] + t * 5.0 * c[5])));
  s.acceleration = 2.0 * c[2] + t * (6.0 * c[3] + t * (12.0 * c[4] + t * 20.0 * c[5]));
  return s;
}

JointSample SplineSegment::sample(double time) const noexcept {
  const double t = time - start_time_;
  if (t < 0.0) return {evaluate(0.0).position, 0.0, 0.0};
  if (t > duration_) return {evaluate(duration_).position, 0.0, 0.0};
  return evaluate(t);
}

bool SplineSegment::finite() const noexcept {
  for (const double c : coefficients_) {
    if (!std::isfinite(c)) return false;
  }
  for (const double t : {0.5 * duration_, duration_}) {
    const JointSample s = evaluate(t);
    if (!std::isfinite(s.position) || !std::isfinite(s.velocity) || !std::isfinite(s.acceleration)) return false;
  }
  return true;
}

}  // namespace servoloop::controllers
