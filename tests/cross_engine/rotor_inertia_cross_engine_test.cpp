// Rotor inertia on both engines, against the two-joint arm's hand-written
// equations of motion with true armature (M(q) + diag(n²·J)) integrated with
// RK4 at 10 µs, closed through the same 1 ms PD loop as cross_engine_test.cpp
// (two_joint_arm.urdf: shoulder 50:1 to shoulder_motor, elbow 1:1 implicit).
//
// mujoco models rotor inertia as joint armature: exact. bullet adds n²·J to
// the child link's inertia about the joint axis: exact for the shoulder (its
// parent is the fixed base), while for the elbow the shoulder feels it too —
// the arm's axes are parallel, so bullet integrates M(q) + k·[[1, 1], [1, 1]]
// instead of M(q) + k·[[0, 0], [0, 1]] (k = n²·J of the elbow).
//
// Tolerances (see cross_engine_test.cpp for their derivation):
//  - mujoco vs the true-armature reference: 1e-5 rad (RK4, O(dt⁴));
//  - bullet vs the model it integrates: dt·max|q̇| (semi-implicit Euler);
//  - bullet vs true armature, elbow case: that bound plus the modelling error,
//    max|q_coupled − q_true| of the two RK4 references, which this test
//    measures and prints (the figure docs/simulation.md quotes).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "bullet_robot_hw.hpp"
#include "mujoco_robot_hw.hpp"
#include "rk4_reference.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "sim_test_support.hpp"

namespace servoloop {
namespace {

namespace hi = hardware_interface;

constexpr double kDt = 0.001;
constexpr double kG = 9.81;
constexpr double kMujocoTolerance = 1e-5;  // rad

const std::string kArmUrdf = std::string(SERVOLOOP_SOURCE_DIR) + "/tests/cross_engine/two_joint_arm.urdf";
constexpr double kL1 = 0.5, kC1 = 0.25, kM1 = 1.5, kI1 = 0.02, kB1 = 0.5;
constexpr double kC2 = 0.2, kM2 = 1.0, kI2 = 0.01, kB2 = 0.2;
constexpr double kElbowLimit = 0.8, kElbowEffort = 20.0;
constexpr double kShoulderReduction = 50.0, kShoulderMotorMaxEffort = 0.3;  // 15 N·m at the joint

struct Trajectory {
  std::vector<Eigen::Vector2d> position;  // sample k: after k control steps
  std::vector<Eigen::Vector2d> velocity;
};

// Joint-space PD to (shoulder, elbow) targets.
Eigen::Vector2d pd(const Eigen::Vector2d& target, const Eigen::Vector2d& q, const Eigen::Vector2d& v) {
  return {40.0 * (target[0] - q[0]) - 6.0 * v[0], 15.0 * (target[1] - q[1]) - 1.5 * v[1]};
}

template <class Backend>
Trajectory runBackend(const std::string& yaml, const Eigen::Vector2d& target, int steps) {
  Backend hw;
  hw.init(sim_testing::makeInfo(sim_testing::readFile(kArmUrdf), yaml, kArmUrdf));
  hw.doSwitch({sim_testing::controllerClaiming("effort", "EffortJointInterface", {"shoulder", "elbow"})}, {});
  hi::JointHandle shoulder = hw.template get<hi::EffortJointInterface>()->getHandle("shoulder");
  hi::JointHandle elbow = hw.template get<hi::EffortJointInterface>()->getHandle("elbow");
  const Duration period(kDt);
  Trajectory out;
  for (int k = 0; k <= steps; ++k) {
    hw.read(Time(), period);
    const Eigen::Vector2d q(shoulder.getPosition(), elbow.getPosition());
    const Eigen::Vector2d v(shoulder.getVelocity(), elbow.getVelocity());
    out.position.push_back(q);
    out.velocity.push_back(v);
    if (k == steps) break;
    const Eigen::Vector2d effort = pd(target, q, v);
    shoulder.setCommand(effort[0]);
    elbow.setCommand(effort[1]);
    hw.write(Time(), period);
    hw.step();
  }
  return out;
}

// The arm's equations of motion (see cross_engine_test.cpp) with an added
// constant joint-space inertia `rotor` (true armature: diagonal).
Eigen::Vector2d armAcceleration(const Eigen::Vector2d& q, const Eigen::Vector2d& v, const Eigen::Vector2d& effort,
                                const Eigen::Matrix2d& rotor) {
  const double cos2 = std::cos(q[1]), sin2 = std::sin(q[1]);
  Eigen::Matrix2d mass;
  mass(0, 0) = kI1 + kI2 + kM1 * kC1 * kC1 + kM2 * (kL1 * kL1 + kC2 * kC2 + 2.0 * kL1 * kC2 * cos2);
  mass(0, 1) = mass(1, 0) = kI2 + kM2 * (kC2 * kC2 + kL1 * kC2 * cos2);
  mass(1, 1) = kI2 + kM2 * kC2 * kC2;
  const double h = kM2 * kL1 * kC2 * sin2;
  const Eigen::Vector2d coriolis(-h * (2.0 * v[0] * v[1] + v[1] * v[1]), h * v[0] * v[0]);
  const Eigen::Vector2d gravity(
      -kG * (kM1 * kC1 * std::cos(q[0]) + kM2 * (kL1 * std::cos(q[0]) + kC2 * std::cos(q[0] + q[1]))),
      -kG * kM2 * kC2 * std::cos(q[0] + q[1]));
  const Eigen::Vector2d damping(kB1 * v[0], kB2 * v[1]);
  return (mass + rotor).ldlt().solve(effort - damping - coriolis - gravity);
}

// SimRobotHW's saturation: the shoulder by its motor through the gear, the
// elbow by its URDF limits (the reference runs stay clear of the stop).
Eigen::Vector2d saturate(const Eigen::Vector2d& effort) {
  const double shoulder_bound = kShoulderReduction * kShoulderMotorMaxEffort;
  return {std::clamp(effort[0], -shoulder_bound, shoulder_bound), std::clamp(effort[1], -kElbowEffort, kElbowEffort)};
}

Trajectory runReference(const Eigen::Matrix2d& rotor, const Eigen::Vector2d& target, int steps) {
  Trajectory out;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(2), v = Eigen::VectorXd::Zero(2);
  for (int k = 0; k <= steps; ++k) {
    out.position.push_back(q);
    out.velocity.push_back(v);
    if (k == steps) break;
    const Eigen::Vector2d effort = saturate(pd(target, q, v));
    const auto period = sim_testing::integrateRk4(
        [&](double, const Eigen::VectorXd& qq, const Eigen::VectorXd& vv) {
          return Eigen::VectorXd(armAcceleration(qq, vv, effort, rotor));
        },
        q, v, kDt, kDt);
    q = period.back().position;
    v = period.back().velocity;
  }
  return out;
}

double maxDeviation(const Trajectory& a, const Trajectory& b) {
  double error = 0.0;
  for (std::size_t k = 0; k < a.position.size(); ++k) {
    error = std::max(error, (a.position[k] - b.position[k]).cwiseAbs().maxCoeff());
  }
  return error;
}

double maxSpeed(const Trajectory& t) {
  double speed = 0.0;
  for (const auto& v : t.velocity) speed = std::max(speed, v.cwiseAbs().maxCoeff());
  return speed;
}

double maxElbow(const Trajectory& t) {
  double elbow = -1e9;
  for (const auto& q : t.position) elbow = std::max(elbow, q[1]);
  return elbow;
}

const Eigen::Vector2d kTarget(-0.6, 0.5);
constexpr int kSteps = 3000;

TEST(CrossEngineRotorInertia, ShoulderRotorBehindTheGearIsExactOnBothEngines) {
  // J = 2e-4 kg·m² behind 50:1: 0.5 kg·m² at the shoulder, about as much as the arm itself.
  const std::string yaml = "actuators: {shoulder_motor: {max_effort: 0.3, rotor_inertia: 2.0e-4}}";
  constexpr double kReflected = 2500.0 * 2.0e-4;
  Eigen::Matrix2d armature = Eigen::Matrix2d::Zero();
  armature(0, 0) = kReflected;
  const Trajectory reference = runReference(armature, kTarget, kSteps);
  ASSERT_LT(maxElbow(reference), kElbowLimit) << "the case must stay clear of the elbow stop";
  ASSERT_GT(maxDeviation(reference, runReference(Eigen::Matrix2d::Zero(), kTarget, kSteps)), 0.05)
      << "the case must tell the rotor inertia apart";
  const Trajectory bullet = runBackend<sim_bullet::BulletRobotHW>(yaml, kTarget, kSteps);
  const Trajectory mujoco = runBackend<sim_mujoco::MujocoRobotHW>(yaml, kTarget, kSteps);

  const double bullet_bound = kDt * maxSpeed(reference);
  const double bullet_error = maxDeviation(bullet, reference);
  const double mujoco_error = maxDeviation(mujoco, reference);
  std::printf("shoulder rotor: |bullet - ref| %.3g rad (bound %.3g), |mujoco - ref| %.3g rad (bound %.3g), "
              "|bullet - mujoco| %.3g rad\n",
              bullet_error, bullet_bound, mujoco_error, kMujocoTolerance, maxDeviation(bullet, mujoco));
  EXPECT_LT(bullet_error, bullet_bound);
  EXPECT_LT(mujoco_error, kMujocoTolerance);
  EXPECT_LT(maxDeviation(bullet, mujoco), bullet_bound + kMujocoTolerance);
}

TEST(CrossEngineRotorInertia, ElbowRotorIsExactOnMujocoAndWithinTheQuantifiedCouplingErrorOnBullet) {
  // 0.01 kg·m² at the elbow (1:1): a fifth of the forearm's 0.05 about its axis.
  const std::string yaml = "actuators: {shoulder_motor: {max_effort: 0.3}, elbow_motor: {rotor_inertia: 0.01}}";
  constexpr double kReflected = 0.01;
  Eigen::Matrix2d armature = Eigen::Matrix2d::Zero();
  armature(1, 1) = kReflected;
  const Eigen::Matrix2d coupled = kReflected * Eigen::Matrix2d::Ones();  // what bullet integrates
  const Trajectory reference = runReference(armature, kTarget, kSteps);
  const Trajectory coupled_reference = runReference(coupled, kTarget, kSteps);
  ASSERT_LT(std::max(maxElbow(reference), maxElbow(coupled_reference)), kElbowLimit)
      << "the case must stay clear of the elbow stop";
  const Trajectory bullet = runBackend<sim_bullet::BulletRobotHW>(yaml, kTarget, kSteps);
  const Trajectory mujoco = runBackend<sim_mujoco::MujocoRobotHW>(yaml, kTarget, kSteps);

  const double bullet_bound = kDt * std::max(maxSpeed(reference), maxSpeed(coupled_reference));
  const double coupling_error = maxDeviation(coupled_reference, reference);
  const double bullet_vs_model = maxDeviation(bullet, coupled_reference);
  const double bullet_vs_true = maxDeviation(bullet, reference);
  const double mujoco_error = maxDeviation(mujoco, reference);
  std::printf("elbow rotor k = %.3g kg·m²: coupling (model) error %.3g rad; |bullet - coupled ref| %.3g rad "
              "(bound %.3g); |bullet - true ref| %.3g rad (bound %.3g); |mujoco - true ref| %.3g rad\n",
              kReflected, coupling_error, bullet_vs_model, bullet_bound, bullet_vs_true,
              coupling_error + bullet_bound, mujoco_error);
  EXPECT_LT(mujoco_error, kMujocoTolerance);
  EXPECT_LT(bullet_vs_model, bullet_bound) << "bullet must integrate the documented coupled model";
  EXPECT_LT(bullet_vs_true, coupling_error + bullet_bound);
  EXPECT_GT(coupling_error, 0.0);
}

}  // namespace
}  // namespace servoloop
