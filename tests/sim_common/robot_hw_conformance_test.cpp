// What every simulation backend does alike through SimRobotHW: one suite,
// instantiated for each backend built (bullet, mujoco, mock), with what differs
// between them (the integrator's hand-calculated or RK4 reference, and how
// close the backend comes to it) as the backend's parameters. The tests that
// hold for one backend only stay in its own folder (tests/sim_mock, …).
//
// The robots: the seed's one-DOF robots (link2: 0.35 kg·m² about joint1, see
// sim_test_support.hpp) and armUrdf's horizontal arm (1 kg at 1 m, 1.01 kg·m²
// about its axis), which feels +9.81·cos q N·m of gravity about +y (q = 0
// horizontal, q > 0 sinking).
#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mock_robot_hw.hpp"
#include "servoloop/hardware_interface/actuator_interfaces.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "sim_test_support.hpp"
#if SERVOLOOP_HAVE_BULLET
#include "bullet_robot_hw.hpp"
#endif
#if SERVOLOOP_HAVE_MUJOCO
#include "mujoco_robot_hw.hpp"
#include "rk4_reference.hpp"
#endif

namespace servoloop::sim_testing {
namespace {

namespace hi = hardware_interface;

constexpr double kDt = kCycleDt;
constexpr Duration kPeriod(kDt);
constexpr double kG = 9.81;
constexpr double kArmInertia = 1.01;  // kg·m² about arm_joint

// A value a backend must reproduce, and how close (absolute).
struct Expected {
  double value;
  double tolerance;
};

// Joint position (rad) and velocity (rad/s).
struct ArmState {
  double position;
  double velocity;
};

// What a backend with a physics engine (gravity, motors bounded by the motor
// effort limit) must reproduce on top of what every backend does.
struct EngineExpectations {
  // The horizontal arm from rest after `steps` steps under a constant joint
  // effort (N·m) and gravity, with `inertia` (kg·m²) about the axis: the
  // backend's reference.
  std::function<ArmState(double effort, double inertia, int steps)> arm_from_rest;
  // How close the arm comes to arm_from_rest when a 0.2 N·m motor lifts it
  // through 50:1 (300 steps), and when the same motor without a gear lets it
  // fall (velocity, 300 steps).
  double lift_position_tolerance;
  double lift_velocity_tolerance;
  double fall_velocity_tolerance;
  // The velocity of the arm that a position motor bounded to 9.5 N·m lets sink
  // (300 steps) against arm_from_rest.
  double sink_velocity_tolerance;
};

struct Backend {
  std::string name;  // the engine's name(), also the test name suffix
  std::function<std::unique_ptr<sim_common::SimRobotHW>()> make;
  // Joint velocity after one step of the seed link upright at rest (no gravity
  // or damping torque yet) under a joint effort (N·m).
  std::function<Expected(double effort)> seed_first_step_velocity;
  // How close seed robot 1 (no damping, gravity off) comes to n·dt·τ/I after
  // n steps of a constant effort.
  double seed_spin_up_tolerance;
  // How close the arm comes to a velocity target (after 500 steps) and to a
  // position target (after 1000 steps, and held there by the emergency stop).
  double motor_velocity_tolerance;
  double motor_position_tolerance;
  std::optional<EngineExpectations> engine;  // none: ideal actuators (mock)
};

void PrintTo(const Backend& backend, std::ostream* os) { *os << backend.name; }

// Semi-implicit Euler's first step from rest: q̇ = τ/I · dt.
Expected semiImplicitSeedFirstStep(double effort) {
  return {effort / kSeedLink2AxisInertia * kDt, 1e-12};
}

std::vector<Backend> allBackends() {
  std::vector<Backend> backends;
#if SERVOLOOP_HAVE_BULLET
  backends.push_back(Backend{
      .name = "bullet",
      .make = [] { return std::make_unique<sim_bullet::BulletRobotHW>(); },
      .seed_first_step_velocity = semiImplicitSeedFirstStep,
      .seed_spin_up_tolerance = 2e-3 * 1.14,  // 0.2 % of the 1.14 rad/s spun up
      .motor_velocity_tolerance = 1e-3,
      .motor_position_tolerance = 1e-3,
      .engine = EngineExpectations{
          // Semi-implicit Euler from rest with cos q ≈ 1:
          // q_n = a·dt²·n(n+1)/2, q̇_n = a·n·dt with a = (τ + g)/I.
          .arm_from_rest =
              [](double effort, double inertia, int steps) {
                const double acceleration = (effort + kG) / inertia;
                return ArmState{acceleration * kDt * kDt * steps * (steps + 1) / 2.0, acceleration * steps * kDt};
              },
          // 2 % of the lift's 8.5 mrad and 56 mrad/s; 3 % of the fall's 2.85
          // rad/s (the arm swings far enough there for cos q to matter); 0.1 %
          // of the sinking arm's velocity.
          .lift_position_tolerance = 0.02 * 0.0085,
          .lift_velocity_tolerance = 0.02 * 0.056,
          .fall_velocity_tolerance = 0.03 * 2.85,
          .sink_velocity_tolerance = 1e-3 * (kG - 9.5) / kArmInertia * 300 * kDt,
      },
  });
#endif
#if SERVOLOOP_HAVE_MUJOCO
  backends.push_back(Backend{
      .name = "mujoco",
      .make = [] { return std::make_unique<sim_mujoco::MujocoRobotHW>(); },
      .seed_first_step_velocity =
          [](double effort) {
            // RK4 resolves the seed's damping (b = 1) within the step: from rest
            // upright, I q̈ = τ − b q̇ gives q̇(dt) = τ/b (1 − exp(−b dt / I)); the
            // gravity torque m g d q that builds up as the link leaves the top
            // adds (m g d / I)(τ / I) dt³ / 6.
            const double inertia = kSeedLink2AxisInertia;
            const double velocity = effort / 1.0 * (1.0 - std::exp(-1.0 * kDt / inertia)) +
                                    (1.0 * kG * 0.5 / inertia) * (effort / inertia) * kDt * kDt * kDt / 6.0;
            return Expected{velocity, 1e-6 * velocity};
          },
      .seed_spin_up_tolerance = 1e-9,
      .motor_velocity_tolerance = 1e-9,
      .motor_position_tolerance = 1e-6,
      .engine = EngineExpectations{
          // RK4 (independent of MuJoCo) of I q̈ = τ + g cos q.
          .arm_from_rest =
              [](double effort, double inertia, int steps) {
                const auto end =
                    integrateRk4([&](double q, double) { return (effort + kG * std::cos(q)) / inertia; }, 0.0, 0.0,
                                 steps * kDt, kDt)
                        .back();
                return ArmState{end.position[0], end.velocity[0]};
              },
          .lift_position_tolerance = 1e-9,
          .lift_velocity_tolerance = 1e-9,
          .fall_velocity_tolerance = 1e-9,
          .sink_velocity_tolerance = 1e-9,
      },
  });
#endif
  // Ideal actuators: motor targets are met exactly, an effort integrates by
  // semi-implicit Euler; no gravity, motors not bounded by effort.
  backends.push_back(Backend{
      .name = "mock",
      .make = [] { return std::make_unique<sim_mock::MockRobotHW>(); },
      .seed_first_step_velocity = semiImplicitSeedFirstStep,
      .seed_spin_up_tolerance = 1e-9,
      .motor_velocity_tolerance = 1e-12,
      .motor_position_tolerance = 1e-12,
      .engine = std::nullopt,
  });
  return backends;
}

std::vector<Backend> engineBackends() {
  std::vector<Backend> backends = allBackends();
  std::erase_if(backends, [](const Backend& backend) { return !backend.engine; });
  return backends;
}

std::string backendName(const ::testing::TestParamInfo<Backend>& info) { return info.param.name; }

// --- Every backend.

class SimRobotHWConformance : public ::testing::TestWithParam<Backend> {
 protected:
  std::unique_ptr<sim_common::SimRobotHW> hw_ = GetParam().make();
};

// 50 N·m asked of seed robot 2's joint1 (effort limit `applied_limit`) for one
// step: the limit is applied before the engine, and the link moves by it.
void expectSeedFirstStepSaturated(sim_common::SimRobotHW& hw, const Backend& backend, double applied_limit) {
  hw.doSwitch({controllerClaiming("joint1_position_controller", "EffortJointInterface", {"joint1"})}, {});
  hi::JointHandle handle = hw.get<hi::EffortJointInterface>()->getHandle("joint1");
  cycle(hw, handle, 50.0);
  EXPECT_DOUBLE_EQ(hw.appliedCommand(JointIndex(0)).value, applied_limit);
  EXPECT_DOUBLE_EQ(handle.getEffort(), applied_limit);
  const Expected velocity = backend.seed_first_step_velocity(applied_limit);
  EXPECT_NEAR(handle.getVelocity(), velocity.value, velocity.tolerance);
}

TEST_P(SimRobotHWConformance, SeedRobot2OffersJoint1ThroughMotor1AndSaturatesEffortBeforeTheEngine) {
  const std::string path = seedUrdfPath(true);
  hw_->init(makeInfo(readFile(path), "", path));
  EXPECT_EQ(hw_->engine().name(), GetParam().name);
  EXPECT_EQ(hw_->get<hi::EffortJointInterface>()->getNames(), std::vector<std::string>{"joint1"});
  EXPECT_EQ(hw_->get<hi::ActuatorStateInterface>()->getNames(), std::vector<std::string>{"motor1"});
  expectSeedFirstStepSaturated(*hw_, GetParam(), 10.0);  // <limit effort="10">
}

TEST_P(SimRobotHWConformance, AYamlEffortLimitLooserThanTheUrdfIsTheOneApplied) {
  // The seed URDF says 10 N·m; the YAML joint limit says 20. SimRobotHW
  // applies the merged limit (20) and the engine does not clamp again at 10.
  const std::string path = seedUrdfPath(true);
  hw_->init(makeInfo(readFile(path), "joint_limits: {joint1: {has_effort_limits: true, max_effort: 20}}", path));
  expectSeedFirstStepSaturated(*hw_, GetParam(), 20.0);
}

TEST_P(SimRobotHWConformance, SeedRobot1ImplicitTransmissionWithoutGravity) {
  const std::string path = seedUrdfPath(false);
  hw_->init(makeInfo(readFile(path), "sim: {gravity: [0, 0, 0]}", path));
  EXPECT_EQ(hw_->transmissions().implicitTransmissionJoints(), std::vector<std::string>{"joint1"});
  hw_->doSwitch({controllerClaiming("e", "EffortJointInterface", {"joint1"})}, {});
  hi::JointHandle handle = hw_->get<hi::EffortJointInterface>()->getHandle("joint1");
  const int n = 200;
  for (int k = 0; k < n; ++k) cycle(*hw_, handle, 2.0);
  EXPECT_NEAR(handle.getVelocity(), n * kDt * 2.0 / kSeedLink2AxisInertia, GetParam().seed_spin_up_tolerance);
}

TEST_P(SimRobotHWConformance, VelocityAndPositionCommandsGoThroughTheMotors) {
  hw_->init(makeInfo(armUrdf(1.0, kAllJointInterfaces), "sim: {gravity: [0, 0, 0]}"));
  hw_->doSwitch({controllerClaiming("v", "VelocityJointInterface", {"arm_joint"})}, {});
  hi::JointHandle velocity = hw_->get<hi::VelocityJointInterface>()->getHandle("arm_joint");
  for (int k = 0; k < 500; ++k) cycle(*hw_, velocity, 0.5);
  EXPECT_NEAR(velocity.getVelocity(), 0.5, GetParam().motor_velocity_tolerance);

  const auto position_controller = controllerClaiming("p", "PositionJointInterface", {"arm_joint"});
  hw_->doSwitch({position_controller}, {controllerClaiming("v", "VelocityJointInterface", {"arm_joint"})});
  hi::JointHandle position = hw_->get<hi::PositionJointInterface>()->getHandle("arm_joint");
  for (int k = 0; k < 1000; ++k) cycle(*hw_, position, -0.3);
  EXPECT_NEAR(position.getPosition(), -0.3, GetParam().motor_position_tolerance);
}

TEST_P(SimRobotHWConformance, EmergencyStopHoldsAPositionControlledArmAgainstGravity) {
  hw_->init(makeInfo(armUrdf(1.0, kAllJointInterfaces)));
  hw_->doSwitch({controllerClaiming("p", "PositionJointInterface", {"arm_joint"})}, {});
  hi::JointHandle position = hw_->get<hi::PositionJointInterface>()->getHandle("arm_joint");
  for (int k = 0; k < 1000; ++k) cycle(*hw_, position, -0.3);
  const double engaged_at = position.getPosition();
  hw_->setEmergencyStop(true);
  for (int k = 0; k < 500; ++k) cycle(*hw_, position, 1.0);
  EXPECT_NEAR(position.getPosition(), engaged_at, GetParam().motor_position_tolerance);
  EXPECT_DOUBLE_EQ(hw_->appliedCommand(JointIndex(0)).value, engaged_at);
}

TEST_P(SimRobotHWConformance, RotorInertiaIsReflectedThroughTheGear) {
  // J = 1e-4 kg·m² behind 50:1: the joint feels 50²·1e-4 = 0.25 kg·m² more.
  hw_->init(makeInfo(armUrdf(50.0, kEffortInterface),
                     "{sim: {gravity: [0, 0, 0]}, actuators: {arm_motor: {rotor_inertia: 1.0e-4}}}"));
  hw_->doSwitch({controllerClaiming("e", "EffortJointInterface", {"arm_joint"})}, {});
  hi::JointHandle joint = hw_->get<hi::EffortJointInterface>()->getHandle("arm_joint");
  cycle(*hw_, joint, 2.0);
  EXPECT_NEAR(joint.getVelocity(), 2.0 * kDt / (kArmInertia + 0.25), 1e-12);
}

TEST_P(SimRobotHWConformance, ResetReturnsToTheInitialState) {
  hw_->init(makeInfo(armUrdf(1.0, kAllJointInterfaces), "sim: {initial_positions: {arm_joint: -0.2}}"));
  hw_->doSwitch({controllerClaiming("v", "VelocityJointInterface", {"arm_joint"})}, {});
  hi::JointHandle handle = hw_->get<hi::VelocityJointInterface>()->getHandle("arm_joint");
  for (int k = 0; k < 10; ++k) cycle(*hw_, handle, 1.0);
  ASSERT_NE(handle.getPosition(), -0.2) << "the arm must have moved before the reset";
  hw_->reset();
  EXPECT_DOUBLE_EQ(handle.getPosition(), -0.2);
  EXPECT_DOUBLE_EQ(handle.getVelocity(), 0.0);
  EXPECT_DOUBLE_EQ(handle.getCommand(), 0.0);
  EXPECT_DOUBLE_EQ(hw_->simTime().seconds, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Backends, SimRobotHWConformance, ::testing::ValuesIn(allBackends()), backendName);

// --- Backends with a physics engine: gravity, and motors bounded by the
// motor effort limit.

class SimRobotHWEngineConformance : public SimRobotHWConformance {
 protected:
  const EngineExpectations& engine() const { return *GetParam().engine; }
};

// The horizontal arm through a `reduction`:1 gear, a motor of at most
// `motor_max_effort` N·m (and `rotor_inertia` kg·m²) asked for far more lift
// (−1000 N·m at the joint) for `steps` steps.
struct LiftResult {
  double joint_position;
  double joint_velocity;
  double joint_effort;
  double motor_velocity;
  double motor_effort;
};

LiftResult lift(const Backend& backend, double reduction, double motor_max_effort, int steps,
                double rotor_inertia = 0.0) {
  std::unique_ptr<sim_common::SimRobotHW> hw = backend.make();
  hw->init(makeInfo(armUrdf(reduction, kEffortInterface),
                    "actuators: {arm_motor: {max_effort: " + std::to_string(motor_max_effort) +
                        ", rotor_inertia: " + std::to_string(rotor_inertia) + "}}"));
  hw->doSwitch({controllerClaiming("e", "EffortJointInterface", {"arm_joint"})}, {});
  hi::JointHandle joint = hw->get<hi::EffortJointInterface>()->getHandle("arm_joint");
  const hi::ActuatorStateHandle motor = hw->get<hi::ActuatorStateInterface>()->getHandle("arm_motor");
  for (int k = 0; k < steps; ++k) cycle(*hw, joint, -1000.0);
  return {joint.getPosition(), joint.getVelocity(), joint.getEffort(), motor.getVelocity(), motor.getEffort()};
}

TEST_P(SimRobotHWEngineConformance, FiftyToOneGearLetsASmallMotorLiftTheArm) {
  // Through 50:1 a 0.2 N·m motor gives −10 N·m against +9.81: the arm rises.
  const int n = 300;
  const LiftResult geared = lift(GetParam(), 50.0, 0.2, n);
  const ArmState reference = engine().arm_from_rest(-10.0, kArmInertia, n);
  EXPECT_NEAR(geared.joint_position, reference.position, engine().lift_position_tolerance);
  EXPECT_NEAR(geared.joint_velocity, reference.velocity, engine().lift_velocity_tolerance);
  EXPECT_LT(geared.joint_position, 0.0) << "the arm must rise";
  EXPECT_NEAR(geared.joint_effort, -10.0, 1e-9);
  EXPECT_NEAR(geared.motor_effort, -0.2, 1e-12);
  EXPECT_NEAR(geared.motor_velocity, 50.0 * geared.joint_velocity, 1e-9);

  // 0.19 N·m through the same gear is 9.5 N·m < 9.81: the arm sinks.
  EXPECT_GT(lift(GetParam(), 50.0, 0.19, n).joint_position, 0.0);
  // The same 0.2 N·m motor without the gear: the arm falls almost freely.
  const LiftResult direct = lift(GetParam(), 1.0, 0.2, n);
  EXPECT_NEAR(direct.joint_velocity, engine().arm_from_rest(-0.2, kArmInertia, n).velocity,
              engine().fall_velocity_tolerance);
  EXPECT_NEAR(direct.joint_effort, -0.2, 1e-12);
}

TEST_P(SimRobotHWEngineConformance, RotorInertiaBehindTheGearSlowsTheArmBySquaredReduction) {
  // 1e-4 kg·m² rotor behind 50:1: the joint feels 50²·1e-4 = 0.25 kg·m² more.
  const int n = 300;
  const LiftResult geared = lift(GetParam(), 50.0, 0.2, n, 1e-4);
  const ArmState reference = engine().arm_from_rest(-10.0, kArmInertia + 0.25, n);
  EXPECT_NEAR(geared.joint_position, reference.position, engine().lift_position_tolerance);
  EXPECT_NEAR(geared.joint_velocity, reference.velocity, engine().lift_velocity_tolerance);
  EXPECT_GT(std::abs(geared.joint_velocity - engine().arm_from_rest(-10.0, kArmInertia, n).velocity), 1e-3)
      << "the rotor inertia must show";
}

TEST_P(SimRobotHWEngineConformance, VelocityCommandsAreBoundedByTheGearedMotor) {
  // 0.1 N·m through 50:1: the velocity motor may use 5 N·m at the joint
  // (the URDF gives no effort limit). No gravity, no damping: from rest
  // v_k = k·dt·5/1.01 until the 3 rad/s target, which takes 0.6 s.
  hw_->init(makeInfo(armUrdf(50.0, kAllJointInterfaces),
                     "{sim: {gravity: [0, 0, 0]}, actuators: {arm_motor: {max_effort: 0.1}}}"));
  hw_->doSwitch({controllerClaiming("v", "VelocityJointInterface", {"arm_joint"})}, {});
  hi::JointHandle joint = hw_->get<hi::VelocityJointInterface>()->getHandle("arm_joint");
  const hi::ActuatorStateHandle motor = hw_->get<hi::ActuatorStateInterface>()->getHandle("arm_motor");
  for (int k = 1; k <= 300; ++k) {
    cycle(*hw_, joint, 3.0);
    ASSERT_NEAR(joint.getVelocity(), k * kDt * 5.0 / kArmInertia, 1e-9) << "cycle " << k;
  }
  EXPECT_NEAR(joint.getEffort(), 5.0, 1e-9);
  EXPECT_NEAR(motor.getEffort(), 0.1, 1e-11);
}

TEST_P(SimRobotHWEngineConformance, PositionCommandsReportTheEffortHoldingTheArm) {
  // What joint_states shows in position mode: the motor's effort, here
  // balancing gravity at rest at −0.3 rad: −9.81·cos(−0.3) N·m.
  hw_->init(makeInfo(armUrdf(1.0, kAllJointInterfaces)));
  hw_->doSwitch({controllerClaiming("p", "PositionJointInterface", {"arm_joint"})}, {});
  hi::JointHandle joint = hw_->get<hi::PositionJointInterface>()->getHandle("arm_joint");
  const hi::ActuatorStateHandle motor = hw_->get<hi::ActuatorStateInterface>()->getHandle("arm_motor");
  for (int k = 0; k < 1500; ++k) cycle(*hw_, joint, -0.3);
  ASSERT_NEAR(joint.getPosition(), -0.3, 1e-6);
  const double holding = -kG * std::cos(-0.3);
  EXPECT_NEAR(joint.getEffort(), holding, 1e-4 * std::abs(holding));
  EXPECT_NEAR(motor.getEffort(), holding, 1e-4 * std::abs(holding));
}

TEST_P(SimRobotHWEngineConformance, PositionCommandsAreBoundedByTheMotorEffortLimit) {
  // 0.19 N·m through 50:1 is 9.5 N·m < the 9.81 N·m gravity needs at the
  // horizontal: the position motor cannot lift the arm and it sinks, with the
  // motor at its bound the whole way.
  hw_->init(makeInfo(armUrdf(50.0, kAllJointInterfaces), "actuators: {arm_motor: {max_effort: 0.19}}"));
  hw_->doSwitch({controllerClaiming("p", "PositionJointInterface", {"arm_joint"})}, {});
  hi::JointHandle joint = hw_->get<hi::PositionJointInterface>()->getHandle("arm_joint");
  for (int k = 0; k < 300; ++k) {
    cycle(*hw_, joint, -0.5);
    ASSERT_NEAR(joint.getEffort(), -9.5, 1e-9) << "cycle " << k;
  }
  EXPECT_NEAR(joint.getVelocity(), engine().arm_from_rest(-9.5, kArmInertia, 300).velocity,
              engine().sink_velocity_tolerance);
  EXPECT_GT(joint.getPosition(), 0.0) << "the arm sinks";
}

TEST_P(SimRobotHWEngineConformance, PositionMotorHoldsTheArmOnlyWhenTheGearedMotorIsStrongEnough) {
  // Holding the horizontal arm needs 9.81 N·m. A 0.2 N·m motor behind 50:1
  // gives 10 N·m: it holds. A 0.19 N·m one gives 9.5 N·m: the arm sags.
  const auto hold = [&](double motor_max_effort) {
    std::unique_ptr<sim_common::SimRobotHW> hw = GetParam().make();
    hw->init(makeInfo(armUrdf(50.0, kAllJointInterfaces),
                      "actuators: {arm_motor: {max_effort: " + std::to_string(motor_max_effort) + "}}"));
    hw->doSwitch({controllerClaiming("p", "PositionJointInterface", {"arm_joint"})}, {});
    hi::JointHandle position = hw->get<hi::PositionJointInterface>()->getHandle("arm_joint");
    double max_effort = 0.0;
    for (int k = 0; k < 1000; ++k) {
      cycle(*hw, position, 0.0);
      max_effort = std::max(max_effort, std::abs(position.getEffort()));
    }
    EXPECT_LE(max_effort, 50.0 * motor_max_effort + 1e-9);
    return position.getPosition();
  };
  EXPECT_NEAR(hold(0.2), 0.0, 1e-3);
  // Sagging under (9.81 − 9.5) N·m: q ≈ ½ · 0.31 / 1.01 · t² = 0.15 rad at 1 s.
  const double sag = hold(0.19);
  EXPECT_GT(sag, 0.1);
  EXPECT_LT(sag, 0.16);
}

TEST_P(SimRobotHWEngineConformance, InitialPositionsAndResetFromTheYaml) {
  const std::string path = seedUrdfPath(true);
  hw_->init(makeInfo(readFile(path), "sim: {initial_positions: {joint1: 0.5}}", path));
  hi::JointHandle handle = hw_->get<hi::EffortJointInterface>()->getHandle("joint1");
  hw_->read(Time(), kPeriod);
  EXPECT_DOUBLE_EQ(handle.getPosition(), 0.5);
  for (int k = 0; k < 100; ++k) cycle(*hw_, handle, 0.0);
  EXPECT_GT(handle.getPosition(), 0.5) << "mode none: zero effort, gravity pulls the link down";
  hw_->reset();
  hw_->read(Time(), kPeriod);
  EXPECT_DOUBLE_EQ(handle.getPosition(), 0.5);
  EXPECT_EQ(handle.getVelocity(), 0.0);
  EXPECT_EQ(hw_->simTime().seconds, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Backends, SimRobotHWEngineConformance, ::testing::ValuesIn(engineBackends()),
                         backendName);
// A build with the mock backend only has no engine to run these on.
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(SimRobotHWEngineConformance);

}  // namespace
}  // namespace servoloop::sim_testing
