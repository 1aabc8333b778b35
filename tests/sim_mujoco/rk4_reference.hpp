#pragma once
// Independent references for the MuJoCo and cross-engine tests: classical
// fourth-order Runge-Kutta for joint-space dynamics q̈ = f(t, q, q̇), written
// here from the textbook formula (no engine code involved).
#include <functional>
#include <vector>

#include <Eigen/Core>

namespace servoloop::sim_testing {

struct JointTrajectorySample {
  Eigen::VectorXd position;
  Eigen::VectorXd velocity;
};

// q̈ = acceleration(t, q, q̇).
using JointAcceleration =
    std::function<Eigen::VectorXd(double, const Eigen::VectorXd&, const Eigen::VectorXd&)>;

// Integrates from (q0, v0) with RK4 at step `h_s` and returns the state at
// every multiple of `sample_period_s` up to `duration_s` (sample 0: the
// initial state). sample_period_s must be a multiple of h_s.
inline std::vector<JointTrajectorySample> integrateRk4(const JointAcceleration& acceleration,
                                                       const Eigen::VectorXd& q0, const Eigen::VectorXd& v0,
                                                       double duration_s, double sample_period_s,
                                                       double h_s = 1e-5) {
  const int substeps = static_cast<int>(sample_period_s / h_s + 0.5);
  const int samples = static_cast<int>(duration_s / sample_period_s + 0.5);
  std::vector<JointTrajectorySample> out;
  out.reserve(static_cast<std::size_t>(samples) + 1);
  Eigen::VectorXd q = q0;
  Eigen::VectorXd v = v0;
  double t = 0.0;
  out.push_back({q, v});
  for (int s = 0; s < samples; ++s) {
    for (int i = 0; i < substeps; ++i) {
      const Eigen::VectorXd k1q = v;
      const Eigen::VectorXd k1v = acceleration(t, q, v);
      const Eigen::VectorXd k2q = v + 0.5 * h_s * k1v;
      const Eigen::VectorXd k2v = acceleration(t + 0.5 * h_s, q + 0.5 * h_s * k1q, k2q);
      const Eigen::VectorXd k3q = v + 0.5 * h_s * k2v;
      const Eigen::VectorXd k3v = acceleration(t + 0.5 * h_s, q + 0.5 * h_s * k2q, k3q);
      const Eigen::VectorXd k4q = v + h_s * k3v;
      const Eigen::VectorXd k4v = acceleration(t + h_s, q + h_s * k3q, k4q);
      q += h_s / 6.0 * (k1q + 2.0 * k2q + 2.0 * k3q + k4q);
      v += h_s / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
      t += h_s;
    }
    out.push_back({q, v});
  }
  return out;
}

// One joint: q̈ = acceleration(q, q̇).
inline std::vector<JointTrajectorySample> integrateRk4(const std::function<double(double, double)>& acceleration,
                                                       double q0, double v0, double duration_s,
                                                       double sample_period_s, double h_s = 1e-5) {
  return integrateRk4(
      [&](double, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
        return Eigen::VectorXd::Constant(1, acceleration(q[0], v[0]));
      },
      Eigen::VectorXd::Constant(1, q0), Eigen::VectorXd::Constant(1, v0), duration_s, sample_period_s, h_s);
}

}  // namespace servoloop::sim_testing
