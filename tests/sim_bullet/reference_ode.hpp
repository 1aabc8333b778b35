#pragma once
// Independent references for the Bullet tests: a classical RK4 integrator for
// one-degree-of-freedom joints, q'' = f(q, q').
#include <functional>
#include <vector>

namespace servoloop::sim_bullet::testing {

struct JointSample {
  double position;
  double velocity;
};

// Integrates q'' = acceleration(q, q') from (q0, v0) with RK4 at step `h_s` and
// returns the state at every multiple of `sample_period_s` up to `duration_s`
// (sample 0 is the initial state). sample_period_s must be a multiple of h_s.
inline std::vector<JointSample> integrateRk4(const std::function<double(double, double)>& acceleration,
                                             double q0, double v0, double duration_s, double sample_period_s,
                                             double h_s = 1e-5) {
  const int substeps = static_cast<int>(sample_period_s / h_s + 0.5);
  const int samples = static_cast<int>(duration_s / sample_period_s + 0.5);
  std::vector<JointSample> out;
  out.reserve(samples + 1);
  double q = q0;
  double v = v0;
  out.push_back({q, v});
  for (int s = 0; s < samples; ++s) {
    for (int i = 0; i < substeps; ++i) {
      const double k1q = v, k1v = acceleration(q, v);
      const double k2q = v + 0.5 * h_s * k1v, k2v = acceleration(q + 0.5 * h_s * k1q, v + 0.5 * h_s * k1v);
      const double k3q = v + 0.5 * h_s * k2v, k3v = acceleration(q + 0.5 * h_s * k2q, v + 0.5 * h_s * k2v);
      const double k4q = v + h_s * k3v, k4v = acceleration(q + h_s * k3q, v + h_s * k3v);
      q += h_s / 6.0 * (k1q + 2 * k2q + 2 * k3q + k4q);
      v += h_s / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    }
    out.push_back({q, v});
  }
  return out;
}

}  // namespace servoloop::sim_bullet::testing
