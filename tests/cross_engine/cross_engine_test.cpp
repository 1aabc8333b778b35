// Cross-engine agreement: the same robots, YAML and commands on the bullet and
// mujoco backends (each through SimRobotHW, so transmissions, motor limits and
// joint limits are the shared code), compared with each other and with an
// independent reference: the robot's equations of motion written by hand and
// integrated with RK4 at 10 µs, closed through the same discrete controller
// (effort held over each 1 ms control period, the same saturation rules).
//
// Tolerances, derived from the step size dt = 1 ms:
//  - mujoco integrates with RK4: its global error is O(dt⁴), ~(ω·dt)⁴ per
//    unit time for the arm's fastest mode ω ≈ 30 rad/s → ~1e-6 rad at most;
//    bound kMujocoTolerance = 1e-5 rad;
//  - bullet integrates with semi-implicit Euler (v += a·dt, then q += v·dt):
//    first order. Each step its position moves dt·v_{k+1} where the exact
//    motion moves dt·(v_k + v_{k+1})/2, so it leads by dt·Δv/2 per step; in a
//    stable closed loop the lead does not accumulate beyond about dt·max|q̇|
//    (the Euler phase error of a damped mode, see docs below). Bound:
//    dt·max|q̇_reference|;
//  - bullet vs mujoco: the sum of the two bounds.
// A modelling error (wrong inertia, gravity, damping, gear or motor limit)
// shows as orders of magnitude more: a 1 % inertia error moves the arm by
// ~1e-2 rad within a second.
// When the engines disagree beyond the bound, the test names the engine that
// is off the reference (see expectAgreement).
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

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
constexpr double kMujocoTolerance = 1e-5;  // rad, see above

// Joint-space effort commands from the measured state at control step k.
using Controller = std::function<Eigen::VectorXd(int k, const Eigen::VectorXd& q, const Eigen::VectorXd& v)>;
// The saturation SimRobotHW applies (joint limits, then motor limits), for the reference.
using Saturation = std::function<Eigen::VectorXd(const Eigen::VectorXd& effort, const Eigen::VectorXd& q,
                                                 const Eigen::VectorXd& v)>;
// q̈ of the robot under joint efforts τ (the hand-written equations of motion).
using Dynamics = std::function<Eigen::VectorXd(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                               const Eigen::VectorXd& effort)>;

struct Trajectory {
  std::vector<Eigen::VectorXd> position;  // sample k: after k control steps
  std::vector<Eigen::VectorXd> velocity;
};

// Runs `Backend` (a SimRobotHW) with every joint in effort mode.
template <class Backend>
Trajectory runBackend(const std::string& urdf_path, const std::string& yaml, const std::vector<std::string>& joints,
                      const Controller& controller, int steps, double dt = kDt) {
  Backend hw;
  hw.init(sim_testing::makeInfo(sim_testing::readFile(urdf_path), yaml, urdf_path));
  std::set<std::string> joint_set(joints.begin(), joints.end());
  hw.doSwitch({sim_testing::controllerClaiming("effort", "EffortJointInterface", joint_set)}, {});
  std::vector<hi::JointHandle> handles;
  for (const auto& joint : joints) handles.push_back(hw.template get<hi::EffortJointInterface>()->getHandle(joint));
  const std::size_t n = joints.size();
  Trajectory out;
  Eigen::VectorXd q(n), v(n);
  const Duration period(dt);
  for (int k = 0; k <= steps; ++k) {
    hw.read(Time(), period);
    for (std::size_t j = 0; j < n; ++j) {
      q[j] = handles[j].getPosition();
      v[j] = handles[j].getVelocity();
    }
    out.position.push_back(q);
    out.velocity.push_back(v);
    if (k == steps) break;
    const Eigen::VectorXd effort = controller(k, q, v);
    for (std::size_t j = 0; j < n; ++j) handles[j].setCommand(effort[j]);
    hw.write(Time(), period);
    hw.step();
  }
  return out;
}

// The reference: the same controller and saturation, the plant by RK4 at h_s.
Trajectory runReference(const Dynamics& dynamics, const Controller& controller, const Saturation& saturate,
                        const Eigen::VectorXd& q0, int steps, double dt = kDt, double h_s = 1e-5) {
  Trajectory out;
  Eigen::VectorXd q = q0;
  Eigen::VectorXd v = Eigen::VectorXd::Zero(q0.size());
  for (int k = 0; k <= steps; ++k) {
    out.position.push_back(q);
    out.velocity.push_back(v);
    if (k == steps) break;
    const Eigen::VectorXd effort = saturate(controller(k, q, v), q, v);
    const auto period = sim_testing::integrateRk4(
        [&](double, const Eigen::VectorXd& qq, const Eigen::VectorXd& vv) { return dynamics(qq, vv, effort); }, q, v,
        dt, dt, h_s);
    q = period.back().position;
    v = period.back().velocity;
  }
  return out;
}

struct Deviation {
  double max_position_error = 0.0;  // rad, over all joints and samples
  int worst_sample = 0;
};

Deviation compare(const Trajectory& a, const Trajectory& b, int first_sample = 0, int last_sample = -1) {
  Deviation d;
  const int last = last_sample < 0 ? static_cast<int>(a.position.size()) - 1 : last_sample;
  for (int k = first_sample; k <= last; ++k) {
    const double error = (a.position[k] - b.position[k]).cwiseAbs().maxCoeff();
    if (error > d.max_position_error) {
      d.max_position_error = error;
      d.worst_sample = k;
    }
  }
  return d;
}

double maxSpeed(const Trajectory& t) {
  double speed = 0.0;
  for (const auto& v : t.velocity) speed = std::max(speed, v.cwiseAbs().maxCoeff());
  return speed;
}

// Bullet within its first-order bound of the reference, mujoco within its
// RK4 bound, and the two within the sum of both; the messages say which
// engine is off the reference when they disagree.
void expectAgreement(const Trajectory& bullet, const Trajectory& mujoco, const Trajectory& reference,
                     const std::string& what) {
  const double bullet_tolerance = kDt * maxSpeed(reference);
  const Deviation bullet_vs_reference = compare(bullet, reference);
  const Deviation mujoco_vs_reference = compare(mujoco, reference);
  const Deviation bullet_vs_mujoco = compare(bullet, mujoco);
  std::printf("%s: |bullet - mujoco| %.3g rad (bound %.3g), |bullet - ref| %.3g rad (bound %.3g), "
              "|mujoco - ref| %.3g rad (bound %.3g)\n",
              what.c_str(), bullet_vs_mujoco.max_position_error, bullet_tolerance + kMujocoTolerance,
              bullet_vs_reference.max_position_error, bullet_tolerance, mujoco_vs_reference.max_position_error,
              kMujocoTolerance);
  EXPECT_LT(bullet_vs_mujoco.max_position_error, bullet_tolerance + kMujocoTolerance)
      << what << ": the engines disagree (worst at t = " << bullet_vs_mujoco.worst_sample * kDt
      << " s); against the reference bullet is off by " << bullet_vs_reference.max_position_error
      << " rad and mujoco by " << mujoco_vs_reference.max_position_error << " rad";
  EXPECT_LT(bullet_vs_reference.max_position_error, bullet_tolerance)
      << what << ": bullet is off the reference (worst at t = " << bullet_vs_reference.worst_sample * kDt << " s)";
  EXPECT_LT(mujoco_vs_reference.max_position_error, kMujocoTolerance)
      << what << ": mujoco is off the reference (worst at t = " << mujoco_vs_reference.worst_sample * kDt << " s)";
}

// ros_control's effort saturation (reference doc): bounds ±e_max, the side
// pushing further out cut to 0 beyond a position limit or the velocity limit.
double saturateEffort(double effort, double q, double v, double e_max, double p_min, double p_max, double v_max) {
  double lower = -e_max, upper = e_max;
  if (q < p_min) {
    lower = 0.0;
  } else if (q > p_max) {
    upper = 0.0;
  }
  if (v < -v_max) {
    lower = 0.0;
  } else if (v > v_max) {
    upper = 0.0;
  }
  return std::clamp(effort, lower, upper);
}

// --- the seed robot under its YAML PID ------------------------------------

// effort_controllers/JointPositionController's PID (control_toolbox):
// p·e + clamp(i·∫e, i_clamp) + d·(0 − q̇), with the seed YAML's gains.
struct SeedPid {
  double p, i, d, i_min, i_max;
  double integral = 0.0;
  double operator()(double error, double velocity) {
    integral += error * kDt;
    return p * error + std::clamp(i * integral, i_min, i_max) + d * (0.0 - velocity);
  }
};

SeedPid seedPidFromYaml() {
  const YAML::Node yaml = YAML::LoadFile(std::string(SERVOLOOP_SEED_DIR) + "/control_config/one_dof_ctl_params.yaml");
  const YAML::Node pid = yaml["one_DOF_robot"]["joint1_position_controller"]["pid"];
  return {pid["p"].as<double>(), pid["i"].as<double>(), pid["d"].as<double>(), pid["i_clamp_min"].as<double>(),
          pid["i_clamp_max"].as<double>()};
}

TEST(CrossEngine, SeedRobotUnderItsYamlPidAgreesOnBothEnginesAndTheReference) {
  const std::string urdf = std::string(SERVOLOOP_SEED_DIR) + "/minimal_robot_description_w_jnt_ctl.urdf";
  const std::string yaml = "sim: {initial_positions: {joint1: 0.5}}";
  constexpr double kTarget = 1.2;
  constexpr int kSteps = 5000;
  // One PID per run (it keeps an integral).
  const auto make_controller = [] {
    auto pid = std::make_shared<SeedPid>(seedPidFromYaml());
    return Controller([pid](int, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
      return Eigen::VectorXd::Constant(1, (*pid)(kTarget - q[0], v[0]));
    });
  };
  const Trajectory bullet = runBackend<sim_bullet::BulletRobotHW>(urdf, yaml, {"joint1"}, make_controller(), kSteps);
  const Trajectory mujoco = runBackend<sim_mujoco::MujocoRobotHW>(urdf, yaml, {"joint1"}, make_controller(), kSteps);

  // Seed link2 about joint1: I = 0.35 kg·m², m g d = 4.905 N·m (q = 0 upright), b = 1.
  const Dynamics seed = [](const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& effort) {
    return Eigen::VectorXd::Constant(1, (effort[0] + 1.0 * kG * 0.5 * std::sin(q[0]) - 1.0 * v[0]) / 0.35);
  };
  // URDF limits: effort 10, position [0, 2], velocity 0.5.
  const Saturation limits = [](const Eigen::VectorXd& effort, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
    return Eigen::VectorXd::Constant(1, saturateEffort(effort[0], q[0], v[0], 10.0, 0.0, 2.0, 0.5));
  };
  const Trajectory reference = runReference(seed, make_controller(), limits, Eigen::VectorXd::Constant(1, 0.5), kSteps);

  // The seed gains are slow (d = 10 against I = 0.35, the integral clamped at
  // 10 N·m): after 5 s the link is within 0.1 rad of the target.
  EXPECT_NEAR(reference.position.back()[0], kTarget, 0.1) << "the PID drives the link to its target";
  expectAgreement(bullet, mujoco, reference, "seed robot, PID to 1.2 rad");
}

// --- the two-joint arm ----------------------------------------------------

const std::string kArmUrdf = std::string(SERVOLOOP_CROSS_ENGINE_DIR) + "/two_joint_arm.urdf";
// two_joint_arm.urdf: link lengths, centres of mass, masses, inertias about the
// centres of mass (y), damping.
constexpr double kL1 = 0.5, kC1 = 0.25, kM1 = 1.5, kI1 = 0.02, kB1 = 0.5;
constexpr double kC2 = 0.2, kM2 = 1.0, kI2 = 0.01, kB2 = 0.2;
constexpr double kElbowLimit = 0.8, kElbowEffort = 20.0;
constexpr double kShoulderReduction = 50.0, kShoulderMotorMaxEffort = 0.3;  // → 15 N·m at the joint
const std::string kArmYaml = "actuators: {shoulder_motor: {max_effort: 0.3}}";

// Planar two-link arm, both axes y, q = 0 horizontal, positive q lowers the
// link (the centre of mass of link 1 is at height 1 − c1·sin q1):
//   M(q) q̈ + c(q, q̇) + G(q) = τ − B q̇
//   M11 = I1 + I2 + m1 c1² + m2 (l1² + c2² + 2 l1 c2 cos q2)
//   M12 = I2 + m2 (c2² + l1 c2 cos q2),  M22 = I2 + m2 c2²
//   c1 = −m2 l1 c2 sin q2 (2 q̇1 q̇2 + q̇2²),  c2 = m2 l1 c2 sin q2 q̇1²
//   G = ∂V/∂q with V = g [m1 (1 − c1 sin q1) + m2 (1 − l1 sin q1 − c2 sin(q1 + q2))]
Eigen::Vector2d armGravity(const Eigen::Vector2d& q) {
  const double g1 = -kG * (kM1 * kC1 * std::cos(q[0]) + kM2 * (kL1 * std::cos(q[0]) + kC2 * std::cos(q[0] + q[1])));
  const double g2 = -kG * kM2 * kC2 * std::cos(q[0] + q[1]);
  return {g1, g2};
}

Eigen::VectorXd armAcceleration(const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& effort) {
  const double cos2 = std::cos(q[1]), sin2 = std::sin(q[1]);
  Eigen::Matrix2d mass;
  mass(0, 0) = kI1 + kI2 + kM1 * kC1 * kC1 + kM2 * (kL1 * kL1 + kC2 * kC2 + 2.0 * kL1 * kC2 * cos2);
  mass(0, 1) = mass(1, 0) = kI2 + kM2 * (kC2 * kC2 + kL1 * kC2 * cos2);
  mass(1, 1) = kI2 + kM2 * kC2 * kC2;
  const double h = kM2 * kL1 * kC2 * sin2;
  const Eigen::Vector2d coriolis(-h * (2.0 * v[0] * v[1] + v[1] * v[1]), h * v[0] * v[0]);
  const Eigen::Vector2d damping(kB1 * v[0], kB2 * v[1]);
  const Eigen::Vector2d rhs = Eigen::Vector2d(effort[0], effort[1]) - damping - coriolis - armGravity(q.head<2>());
  return mass.ldlt().solve(rhs);
}

// The shoulder is bounded by its motor through the gear (no URDF effort
// limit); the elbow by its URDF limits.
Eigen::VectorXd armSaturation(const Eigen::VectorXd& effort, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  const double shoulder_bound = kShoulderReduction * kShoulderMotorMaxEffort;
  Eigen::VectorXd out(2);
  out[0] = std::clamp(effort[0], -shoulder_bound, shoulder_bound);
  out[1] = saturateEffort(effort[1], q[1], v[1], kElbowEffort, -kElbowLimit, kElbowLimit, 100.0);
  return out;
}

// Joint-space PD to (shoulder, elbow) targets; gains per joint.
Controller armPd(double shoulder_target, double elbow_target) {
  return [=](int, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
    Eigen::VectorXd effort(2);
    effort[0] = 40.0 * (shoulder_target - q[0]) - 6.0 * v[0];
    effort[1] = 15.0 * (elbow_target - q[1]) - 1.5 * v[1];
    return effort;
  };
}

const std::vector<std::string> kArmJoints = {"shoulder", "elbow"};

TEST(CrossEngine, TwoJointArmRaisedThroughTheGearAgreesOnBothEnginesAndTheReference) {
  // From horizontal (gravity load 10.5 N·m at the shoulder) to shoulder −0.6
  // (raised), elbow 0.5: the shoulder PD asks for more than the motor's
  // 15 N·m at first, so the motor limit through the 50:1 gear shapes the rise.
  constexpr int kSteps = 3000;
  const Controller pd = armPd(-0.6, 0.5);
  const Trajectory bullet = runBackend<sim_bullet::BulletRobotHW>(kArmUrdf, kArmYaml, kArmJoints, pd, kSteps);
  const Trajectory mujoco = runBackend<sim_mujoco::MujocoRobotHW>(kArmUrdf, kArmYaml, kArmJoints, pd, kSteps);
  const Trajectory reference = runReference(armAcceleration, pd, armSaturation, Eigen::VectorXd::Zero(2), kSteps);
  EXPECT_GT(std::abs(pd(0, Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(2))[0]),
            kShoulderReduction * kShoulderMotorMaxEffort)
      << "the case must saturate the shoulder motor";
  expectAgreement(bullet, mujoco, reference, "two-joint arm, raise");
}

TEST(CrossEngine, BulletErrorIsFirstOrderInTheStep) {
  // Halving the step halves bullet's distance from the reference (semi-implicit
  // Euler is first order): the disagreement is integration error, not model.
  const auto bullet_error = [](double dt) {
    const int steps = static_cast<int>(1.0 / dt + 0.5);
    const std::string yaml = kArmYaml + ", sim: {time_step: " + std::to_string(dt) + "}";
    const Controller pd = armPd(-0.6, 0.5);
    const Trajectory bullet =
        runBackend<sim_bullet::BulletRobotHW>(kArmUrdf, "{" + yaml + "}", kArmJoints, pd, steps, dt);
    const Trajectory reference =
        runReference(armAcceleration, pd, armSaturation, Eigen::VectorXd::Zero(2), steps, dt);
    return compare(bullet, reference).max_position_error;
  };
  const double coarse = bullet_error(0.002);
  const double fine = bullet_error(0.001);
  std::printf("bullet vs reference: %.3g rad at dt = 2 ms, %.3g rad at 1 ms (ratio %.2f)\n", coarse, fine,
              coarse / fine);
  EXPECT_NEAR(coarse / fine, 2.0, 0.5);
}

TEST(CrossEngine, TwoJointArmHeldAtTheElbowStopAgreesWithTheStaticEquilibrium) {
  // The elbow PD aims at 1.5 rad, beyond the 0.8 rad stop: both engines must
  // follow the reference until the stop, then rest on it, with the shoulder
  // where its PD balances gravity with the elbow at 0.8 rad.
  constexpr double kShoulderTarget = -0.6;
  constexpr int kSteps = 3000;
  const Controller pd = armPd(kShoulderTarget, 1.5);
  const Trajectory bullet = runBackend<sim_bullet::BulletRobotHW>(kArmUrdf, kArmYaml, kArmJoints, pd, kSteps);
  const Trajectory mujoco = runBackend<sim_mujoco::MujocoRobotHW>(kArmUrdf, kArmYaml, kArmJoints, pd, kSteps);
  const Trajectory reference = runReference(armAcceleration, pd, armSaturation, Eigen::VectorXd::Zero(2), kSteps);

  // Until the reference (which has no stop) reaches the limit, all agree.
  int contact = 0;
  while (contact < kSteps && reference.position[contact][1] < kElbowLimit) ++contact;
  ASSERT_LT(contact, kSteps) << "the elbow must reach its stop";
  ASSERT_GT(contact, 50);
  Trajectory before_bullet{{bullet.position.begin(), bullet.position.begin() + contact}, {}};
  Trajectory before_mujoco{{mujoco.position.begin(), mujoco.position.begin() + contact}, {}};
  Trajectory before_reference{{reference.position.begin(), reference.position.begin() + contact},
                              {reference.velocity.begin(), reference.velocity.begin() + contact}};
  before_bullet.velocity = before_reference.velocity;
  before_mujoco.velocity = before_reference.velocity;
  expectAgreement(before_bullet, before_mujoco, before_reference, "two-joint arm, before the elbow stop");

  // At rest on the stop: the shoulder solves 40 (target − q1) = G1(q1, 0.8)
  // (Newton on the hand-written gravity).
  double q1 = kShoulderTarget;
  for (int i = 0; i < 50; ++i) {
    const double f = 40.0 * (kShoulderTarget - q1) - armGravity({q1, kElbowLimit})[0];
    const double h = 1e-7;
    const double df = (40.0 * (kShoulderTarget - q1 - h) - armGravity({q1 + h, kElbowLimit})[0] - f) / h;
    q1 -= f / df;
  }
  // Stop softness: bullet's stop corrects its penetration softly per step
  // (its own tests allow 0.01 rad), mujoco's sinks ~1e-5 rad (time constant 2 dt).
  constexpr double kBulletStopTolerance = 0.01;
  constexpr double kMujocoStopTolerance = 1e-4;
  std::printf("elbow stop: bullet elbow %.6f shoulder %.6f, mujoco elbow %.6f shoulder %.6f, static shoulder %.6f\n",
              bullet.position.back()[1], bullet.position.back()[0], mujoco.position.back()[1],
              mujoco.position.back()[0], q1);
  EXPECT_NEAR(bullet.position.back()[1], kElbowLimit, kBulletStopTolerance);
  EXPECT_NEAR(mujoco.position.back()[1], kElbowLimit, kMujocoStopTolerance);
  // dq1/dq2 of the equilibrium is below 1, so the shoulders sit within the same bounds.
  EXPECT_NEAR(bullet.position.back()[0], q1, kBulletStopTolerance);
  EXPECT_NEAR(mujoco.position.back()[0], q1, kMujocoStopTolerance);
}

}  // namespace
}  // namespace servoloop
