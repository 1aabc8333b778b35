// Joint-space physics of the MuJoCo engine on the seed robots and small
// inline robots, against analytic solutions and RK4 references.
//
// Error budget: the engine integrates with RK4 (global error O(dt⁴)). At
// dt = 1 ms for the motions below (ω ≤ 4 rad/s, amplitudes ≤ 1 rad) that is
// ~(ω·dt)⁴·(ω·T) ≈ 1e-9 rad over 10 s; the references run RK4 at 10 µs. The
// bounds (1e-6 rad, 1e-6 J) leave three orders of margin and are still a
// thousand times tighter than any modelling error would give (a 0.1 % wrong
// inertia shifts the pendulum by ~1e-3 rad within a few periods).
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <urdf_parser/urdf_parser.h>

#include "rk4_reference.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/sim_mujoco/mjcf_from_urdf.hpp"
#include "servoloop/sim_mujoco/mujoco_physics.hpp"

namespace servoloop::sim_mujoco {
namespace {

using sim_common::EngineJointConfig;
using sim_common::SimSettings;
using sim_testing::integrateRk4;

constexpr double kG = 9.81;
constexpr double kInf = std::numeric_limits<double>::infinity();
const std::string kSeedDir = std::string(SERVOLOOP_SEED_DIR) + "/";
const std::string kAssetsDir = std::string(SERVOLOOP_SOURCE_DIR) + "/tests/assets/";

std::shared_ptr<const urdf::ModelInterface> seedPendulum() {  // continuous joint1, no damping
  return loadRobotModelFile(kSeedDir + "minimal_robot_description.urdf");
}
std::shared_ptr<const urdf::ModelInterface> seedWithControl() {  // revolute [0, 2], effort 10, damping 1
  return loadRobotModelFile(kSeedDir + "minimal_robot_description_w_jnt_ctl.urdf");
}

// Seed link2: m = 1, COM 0.5 m from joint1 along the link, Iyy_com = 0.1.
constexpr double kSeedMass = 1.0;
constexpr double kSeedComDistance = 0.5;
constexpr double kSeedInertiaAboutJoint = 0.1 + kSeedMass * kSeedComDistance * kSeedComDistance;  // 0.35

SimSettings withGravity(bool on = true) {
  SimSettings settings;
  if (!on) settings.gravity = Eigen::Vector3d::Zero();
  return settings;
}

EngineJointConfig jointConfig(const std::string& name, double motor_effort_limit = kInf,
                              double rotor_inertia = 0.0, double initial_position = 0.0) {
  EngineJointConfig config;
  config.name = name;
  config.motor_effort_limit = motor_effort_limit;
  config.reflected_rotor_inertia = rotor_inertia;
  config.initial_position = initial_position;
  return config;
}

void initEngine(MujocoPhysics& engine, const urdf::ModelInterface& model, const SimSettings& settings,
                const std::vector<EngineJointConfig>& joints) {
  engine.init(model, settings, joints, model.getName() + ".urdf");
}

TEST(MujocoPhysics, SeedRobotBecomesOneHingeOnAFixedBase) {
  MujocoPhysics engine;
  initEngine(engine, *seedWithControl(), withGravity(), {jointConfig("joint1", 10.0, 0.0, 0.5)});
  EXPECT_STREQ(engine.name(), "mujoco");
  EXPECT_DOUBLE_EQ(engine.jointPosition(0), 0.5);
  EXPECT_EQ(engine.jointVelocity(0), 0.0);
  const std::string& mjcf = engine.mjcf();
  EXPECT_NE(mjcf.find("<joint name=\"joint1\" type=\"hinge\""), std::string::npos) << mjcf;
  EXPECT_NE(mjcf.find("range=\"0 2\""), std::string::npos) << mjcf;
  EXPECT_NE(mjcf.find("damping=\"1\""), std::string::npos) << mjcf;
  EXPECT_NE(mjcf.find("integrator=\"RK4\""), std::string::npos) << mjcf;
  EXPECT_EQ(mjcf.find("freejoint"), std::string::npos) << "root 'world': fixed base";
  // link1 is glued to the world; joint1 (link2's frame) sits 1 m above it.
  const auto link1 = engine.linkWorldPosition("link1");
  const auto link2 = engine.linkWorldPosition("link2");
  EXPECT_NEAR(link1[2], 0.0, 1e-12);
  EXPECT_NEAR(link2[2], 1.0, 1e-12);
  EXPECT_THROW(engine.linkWorldPosition("no_such_link"), Error);
}

TEST(MujocoPhysics, UnknownJointIsAConfigError) {
  MujocoPhysics engine;
  try {
    initEngine(engine, *seedPendulum(), withGravity(), {jointConfig("glue_robot_to_world")});
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("joint 'glue_robot_to_world'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("one_DOF_robot.urdf"), std::string::npos) << e.what();
  }
}

TEST(MujocoPhysics, UndampedPendulumConservesEnergyAndMatchesRk4) {
  // Link2 points up at q = 0: q̈ = m g d sin(q) / I. Starts 0.5 rad from hanging
  // down, so it swings through link1's collision box: the link must not touch
  // its parent (a contact would stop the swing at once).
  MujocoPhysics engine;
  const double q0 = M_PI - 0.5;
  initEngine(engine, *seedPendulum(), withGravity(), {jointConfig("joint1", kInf, 0.0, q0)});
  const double mgd = kSeedMass * kG * kSeedComDistance;
  const auto energy = [&](double q, double v) { return 0.5 * kSeedInertiaAboutJoint * v * v + mgd * std::cos(q); };
  const double dt = 0.001;
  const auto reference =
      integrateRk4([&](double q, double) { return mgd * std::sin(q) / kSeedInertiaAboutJoint; }, q0, 0.0, 10.0, dt);

  const double e0 = energy(q0, 0.0);
  double max_energy_error = 0.0;
  double max_position_error = 0.0;
  int contacts = 0;
  for (std::size_t k = 1; k < reference.size(); ++k) {
    engine.step();
    max_energy_error = std::max(max_energy_error, std::abs(energy(engine.jointPosition(0), engine.jointVelocity(0)) - e0));
    max_position_error = std::max(max_position_error, std::abs(engine.jointPosition(0) - reference[k].position[0]));
    contacts += engine.contactCount();
  }
  EXPECT_NEAR(engine.time(), 10.0, 1e-9);
  EXPECT_EQ(contacts, 0);
  EXPECT_LT(max_energy_error, 1e-6);    // swing energy 0.60 J
  EXPECT_LT(max_position_error, 1e-6);  // rad
}

TEST(MujocoPhysics, SeedDampingDecaysVelocityExponentially) {
  // No gravity; b = 1 from the seed URDF: v(t) = v0 exp(-b t / I), travel v0 I / b (1 - exp(-b t / I)).
  MujocoPhysics engine;
  initEngine(engine, *seedWithControl(), withGravity(false), {jointConfig("joint1", 10.0)});
  const double v0 = 0.5;
  engine.setJointState(0, 1.0, v0);  // travels at most 0.175 rad: stays inside [0, 2]
  for (int k = 0; k < 1000; ++k) engine.step();
  const double decay = std::exp(-1.0 * engine.time() / kSeedInertiaAboutJoint);
  // RK4 per step reproduces exp(-x) to x⁵/120 (x = b dt / I = 0.003): ~1e-13 over the run.
  EXPECT_NEAR(engine.jointVelocity(0), v0 * decay, 1e-9);
  EXPECT_NEAR(engine.jointPosition(0) - 1.0, v0 * kSeedInertiaAboutJoint * (1.0 - decay), 1e-9);
}

const char* kSliderUrdf = R"(<robot name="slider"><link name="world"/>
    <joint name="lift" type="prismatic"><parent link="world"/><child link="carriage"/>
      <axis xyz="0 0 1"/><limit lower="LOWER" upper="1000" effort="100" velocity="100"/></joint>
    <link name="carriage"><inertial><mass value="3"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link></robot>)";

std::shared_ptr<const urdf::ModelInterface> slider(const std::string& lower) {
  std::string xml = kSliderUrdf;
  xml.replace(xml.find("LOWER"), 5, lower);
  return parseRobotModel(xml, "slider.urdf");
}

TEST(MujocoPhysics, PrismaticJointFallsFreely) {
  MujocoPhysics engine;
  initEngine(engine, *slider("-1000"), withGravity(), {jointConfig("lift")});
  for (int k = 1; k <= 1000; ++k) {
    engine.step();
    const double t = engine.time();
    // Constant acceleration: RK4 is exact (to rounding).
    ASSERT_NEAR(engine.jointPosition(0), -0.5 * kG * t * t, 1e-9) << "t = " << t;
    ASSERT_NEAR(engine.jointVelocity(0), -kG * t, 1e-9) << "t = " << t;
  }
  EXPECT_NEAR(engine.linkWorldPosition("carriage")[2], engine.jointPosition(0), 1e-12);
}

TEST(MujocoPhysics, LimitStopsAFallingSlider) {
  MujocoPhysics engine;
  initEngine(engine, *slider("-0.1"), withGravity(), {jointConfig("lift")});
  for (int k = 0; k < 1000; ++k) engine.step();
  EXPECT_NEAR(engine.jointPosition(0), -0.1, 1e-4);
  EXPECT_NEAR(engine.jointVelocity(0), 0.0, 1e-4);
}

TEST(MujocoPhysics, LimitHoldsAgainstFullEffort) {
  MujocoPhysics engine;
  initEngine(engine, *seedWithControl(), withGravity(), {jointConfig("joint1", 10.0, 0.0, 1.5)});
  // +10 N m (the effort limit) plus gravity (m g d sin q = 4.5 N m near q = 2)
  // push into the upper stop at 2 rad; without the stop the link would pass pi.
  double max_position = 0.0;
  double impact_speed = 0.0;
  for (int k = 0; k < 2000; ++k) {
    engine.setJointEffort(0, 10.0);
    engine.step();
    max_position = std::max(max_position, engine.jointPosition(0));
    impact_speed = std::max(impact_speed, engine.jointVelocity(0));
  }
  // The stop is a soft constraint, a critically damped spring with time
  // constant tc = 2 dt: hit at speed v it sinks in by at most v·tc/e
  // (x(t) = v t e^(−t/tc), largest at t = tc). Held by a steady push of
  // a = 14.5 N·m / 0.35 kg·m², it sits about (1 − d)/d · a · tc² = 8.7e-6 rad
  // deep (impedance d = 0.95 near the stop); bound twice that.
  const double tc = 2.0 * 0.001;
  EXPECT_GT(impact_speed, 5.0) << "the link must hit the stop hard";
  EXPECT_LT(max_position, 2.0 + impact_speed * tc / std::exp(1.0));
  EXPECT_NEAR(engine.jointPosition(0), 2.0, 2.0 * 0.05 / 0.95 * (14.5 / 0.35) * tc * tc);
  EXPECT_NEAR(engine.jointVelocity(0), 0.0, 1e-6);
}

TEST(MujocoPhysics, EffortActsForOneStepOnly) {
  MujocoPhysics engine;
  initEngine(engine, *seedPendulum(), withGravity(false), {jointConfig("joint1")});
  engine.setJointEffort(0, 3.5);
  engine.step();
  const double v1 = engine.jointVelocity(0);
  EXPECT_NEAR(v1, 3.5 / kSeedInertiaAboutJoint * 0.001, 1e-12);
  EXPECT_DOUBLE_EQ(engine.jointEffort(0), 3.5);
  engine.step();
  EXPECT_NEAR(engine.jointVelocity(0), v1, 1e-15);
  EXPECT_EQ(engine.jointEffort(0), 0.0);
}

TEST(MujocoPhysics, OffDiagonalRotatedInertiaSwingsAsTheProjectedTensorSays) {
  // Inertial frame rotated and tensor full: only aᵀ R I Rᵀ a + m |c⊥|² about
  // the joint axis a = y matters for a single hinge.
  const double m = 1.5;
  const Eigen::Vector3d c(0.1, 0.05, -0.2);
  const Eigen::Vector3d rpy(0.4, -0.3, 0.7);
  Eigen::Matrix3d inertia;
  inertia << 0.20, 0.03, 0.02,  //
      0.03, 0.12, -0.04,        //
      0.02, -0.04, 0.15;
  // A physical tensor: principal moments obey the triangle inequality, which
  // MuJoCo checks.
  const Eigen::Vector3d principal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia).eigenvalues();
  ASSERT_GE(principal[0] + principal[1], principal[2]);
  const std::string xml = R"(<robot name="tumbler"><link name="world"/>
    <joint name="hinge" type="continuous"><parent link="world"/><child link="body"/>
      <origin xyz="0 0 2"/><axis xyz="0 1 0"/></joint>
    <link name="body"><inertial><origin xyz="0.1 0.05 -0.2" rpy="0.4 -0.3 0.7"/><mass value="1.5"/>
      <inertia ixx="0.20" ixy="0.03" ixz="0.02" iyy="0.12" iyz="-0.04" izz="0.15"/></inertial></link></robot>)";
  // URDF rpy: R = Rz(yaw) Ry(pitch) Rx(roll).
  const Eigen::Matrix3d r = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  const double inertia_about_axis = (r * inertia * r.transpose())(1, 1) + m * (c.x() * c.x() + c.z() * c.z());
  const double naive_inertia_about_axis = inertia(1, 1) + m * (c.x() * c.x() + c.z() * c.z());
  ASSERT_GT(std::abs(inertia_about_axis - naive_inertia_about_axis), 0.1 * naive_inertia_about_axis)
      << "the case must tell a rotated tensor from an unrotated one";

  MujocoPhysics engine;
  const double q0 = 1.0;
  initEngine(engine, *parseRobotModel(xml, "tumbler.urdf"), withGravity(), {jointConfig("hinge", kInf, 0.0, q0)});
  // Gravity torque about y of the COM rotated by q about y: m g (cx cos q + cz sin q).
  const auto acceleration = [&](double q, double) {
    return m * kG * (c.x() * std::cos(q) + c.z() * std::sin(q)) / inertia_about_axis;
  };
  const auto reference = integrateRk4(acceleration, q0, 0.0, 3.0, 0.001);
  double max_error = 0.0;
  for (std::size_t k = 1; k < reference.size(); ++k) {
    engine.step();
    max_error = std::max(max_error, std::abs(engine.jointPosition(0) - reference[k].position[0]));
  }
  EXPECT_LT(max_error, 1e-6);
}

TEST(MujocoPhysics, RotorInertiaIsTheJointArmatureExactly) {
  // The seed pendulum with 0.25 kg·m² of reflected rotor inertia (e.g. 1e-4
  // kg·m² behind a 50:1 gear): q̈ = m g d sin q / (I + n²J), and a constant
  // effort in zero gravity accelerates it at τ / (I + n²J).
  const double rotor = 0.25;
  const double q0 = M_PI - 0.5;
  MujocoPhysics engine;
  initEngine(engine, *seedPendulum(), withGravity(), {jointConfig("joint1", kInf, rotor, q0)});
  EXPECT_NE(engine.mjcf().find("armature=\"0.25\""), std::string::npos) << engine.mjcf();
  const double mgd = kSeedMass * kG * kSeedComDistance;
  const auto with_rotor = integrateRk4(
      [&](double q, double) { return mgd * std::sin(q) / (kSeedInertiaAboutJoint + rotor); }, q0, 0.0, 5.0, 0.001);
  const auto without_rotor = integrateRk4(
      [&](double q, double) { return mgd * std::sin(q) / kSeedInertiaAboutJoint; }, q0, 0.0, 5.0, 0.001);
  double max_error = 0.0;
  double max_difference_without = 0.0;
  for (std::size_t k = 1; k < with_rotor.size(); ++k) {
    engine.step();
    max_error = std::max(max_error, std::abs(engine.jointPosition(0) - with_rotor[k].position[0]));
    max_difference_without =
        std::max(max_difference_without, std::abs(engine.jointPosition(0) - without_rotor[k].position[0]));
  }
  EXPECT_LT(max_error, 1e-6);
  EXPECT_GT(max_difference_without, 0.1) << "the rotor inertia must change the swing";

  MujocoPhysics pushed;
  initEngine(pushed, *seedPendulum(), withGravity(false), {jointConfig("joint1", kInf, rotor)});
  for (int k = 0; k < 500; ++k) {
    pushed.setJointEffort(0, 2.0);
    pushed.step();
  }
  const double t = pushed.time();
  EXPECT_NEAR(pushed.jointVelocity(0), 2.0 / (kSeedInertiaAboutJoint + rotor) * t, 1e-12);
  EXPECT_NEAR(pushed.jointPosition(0), 0.5 * 2.0 / (kSeedInertiaAboutJoint + rotor) * t * t, 1e-12);
}

TEST(MujocoPhysics, VelocityMotorReachesTargetInOneStepWhenTheBoundAllows) {
  MujocoPhysics engine;
  initEngine(engine, *seedWithControl(), withGravity(), {jointConfig("joint1", 10.0, 0.0, 0.5)});
  engine.setJointVelocityTarget(0, 0.3);
  engine.step();
  // Needs I·0.3/dt ≈ 105 N·m: bounded by 10 N·m, so it ramps (gravity pulls at
  // m g d sin 0.5 = 2.35 N·m, damping b·v is small).
  EXPECT_NEAR(engine.jointEffort(0), 10.0, 1e-12);
  for (int k = 0; k < 300; ++k) engine.step();
  EXPECT_NEAR(engine.jointVelocity(0), 0.3, 1e-4);
  // Holding 0.3 rad/s: the motor balances gravity and damping: m g d sin q + b v.
  EXPECT_NEAR(engine.jointEffort(0), -(kSeedMass * kG * kSeedComDistance * std::sin(engine.jointPosition(0))) + 0.3,
              0.01);
}

TEST(MujocoPhysics, VelocityMotorAcceleratesAtTheEffortBound) {
  // Zero gravity, bound 0.7 N·m: q̈ = 0.7 / (0.35 + 0.35 rotor) = 1 rad/s² until 0.5 rad/s.
  MujocoPhysics engine;
  initEngine(engine, *seedPendulum(), withGravity(false), {jointConfig("joint1", 0.7, 0.35)});
  for (int k = 0; k < 200; ++k) {
    engine.setJointVelocityTarget(0, 0.5);
    engine.step();
  }
  EXPECT_NEAR(engine.jointVelocity(0), 0.2, 1e-9);
  EXPECT_DOUBLE_EQ(engine.jointEffort(0), 0.7);
  for (int k = 0; k < 400; ++k) engine.step();  // the target stays in force
  EXPECT_NEAR(engine.jointVelocity(0), 0.5, 1e-9);
  EXPECT_NEAR(engine.jointEffort(0), 0.0, 1e-9);
}

TEST(MujocoPhysics, PositionMotorApproachesWithItsTimeConstantAndHoldsAgainstGravity) {
  MujocoPhysics engine;
  initEngine(engine, *seedWithControl(), withGravity(), {jointConfig("joint1", 10.0, 0.0, 0.5)});
  engine.setJointPositionTarget(0, 1.2);
  // The motor asks for q̇ = (target − q)/τ each step. The first step would
  // need I·(0.7/τ)/dt ≈ 12 kN·m: saturated at 10 N·m it reaches 5.5 rad/s,
  // cannot brake in time (16 rad/s² at most against gravity) and overshoots
  // by 0.5 rad, as a real 10 N·m motor would; it has settled after 2 s.
  for (int k = 0; k < 2000; ++k) engine.step();
  EXPECT_NEAR(engine.jointPosition(0), 1.2, 1e-6);
  EXPECT_NEAR(engine.jointVelocity(0), 0.0, 1e-6);
  // Holding: the motor carries the gravity torque.
  EXPECT_NEAR(engine.jointEffort(0), -kSeedMass * kG * kSeedComDistance * std::sin(1.2), 1e-3);

  // Unsaturated first-order approach: 1 mrad step, error after τ = 20 ms ≈ e⁻¹
  // of it. In discrete time the position follows the commanded velocity
  // within the step, an O(dt/τ) = 5 % difference; bound 10 %.
  const double start = engine.jointPosition(0);
  engine.setJointPositionTarget(0, start + 0.001);
  for (int k = 0; k < 20; ++k) engine.step();
  EXPECT_NEAR(start + 0.001 - engine.jointPosition(0), 0.001 * std::exp(-1.0), 0.1 * 0.001 * std::exp(-1.0));
}

TEST(MujocoPhysics, ResetRestoresInitialStateAndEffortMode) {
  MujocoPhysics engine;
  initEngine(engine, *seedWithControl(), withGravity(false), {jointConfig("joint1", 10.0, 0.0, 0.4)});
  engine.setJointState(0, 1.0, 0.3);
  engine.setJointVelocityTarget(0, 0.4);
  for (int k = 0; k < 50; ++k) engine.step();
  engine.reset();
  EXPECT_EQ(engine.time(), 0.0);
  EXPECT_DOUBLE_EQ(engine.jointPosition(0), 0.4);
  EXPECT_EQ(engine.jointVelocity(0), 0.0);
  for (int k = 0; k < 50; ++k) engine.step();  // no motor left: zero gravity, at rest
  EXPECT_DOUBLE_EQ(engine.jointPosition(0), 0.4);
}

// A 0.2 m cube as the root link (floating base), box or STL mesh collision.
// The base starts at the origin, so the cube sits 0.5 m above its link frame:
// its bottom starts 0.4 m above the ground and it rests with the link frame
// at z = 0.1 − 0.5 = −0.4.
std::string floatingCubeUrdf(const std::string& geometry) {
  return R"(<robot name="cube"><link name="cube"><inertial><origin xyz="0 0 0.5"/><mass value="2"/>
    <inertia ixx="0.0133" ixy="0" ixz="0" iyy="0.0133" iyz="0" izz="0.0133"/></inertial>
    <collision><origin xyz="0 0 0.5"/><geometry>)" +
         geometry + R"(</geometry></collision></link></robot>)";
}

double heightAfterTwoSeconds(const std::string& urdf, bool ground_plane) {
  SimSettings settings;
  settings.ground_plane = ground_plane;
  MujocoPhysics engine;
  engine.init(*parseRobotModel(urdf, "cube.urdf"), settings, {}, "cube.urdf");
  for (int k = 0; k < 2000; ++k) engine.step();
  return engine.linkWorldPosition("cube")[2];
}

TEST(MujocoPhysics, FloatingBaseFallsFreelyOrRestsOnTheGroundPlane) {
  const std::string box = R"(<box size="0.2 0.2 0.2"/>)";
  // No plane: free fall for 2 s.
  EXPECT_NEAR(heightAfterTwoSeconds(floatingCubeUrdf(box), false), -0.5 * kG * 4.0, 1e-6);
  // On the plane (MuJoCo's soft contact: within 5 mm).
  EXPECT_NEAR(heightAfterTwoSeconds(floatingCubeUrdf(box), true), -0.4, 5e-3);
  for (const std::string file : {"cube_binary.stl", "cube_ascii.stl"}) {
    const std::string mesh = R"(<mesh filename=")" + kAssetsDir + "meshes/" + file + R"("/>)";
    EXPECT_NEAR(heightAfterTwoSeconds(floatingCubeUrdf(mesh), true), -0.4, 5e-3) << file;
  }
  // A 0.2 x 0.4 x 0.6 m box in COLLADA (written in cm) and OBJ: its bottom is
  // 0.3 m below its centre, so the link frame rests at 0.3 - 0.5 = -0.2.
  for (const std::string file : {"box_20x40x60cm_zup.dae", "box_20x40x60cm.obj"}) {
    const std::string mesh = R"(<mesh filename=")" + kAssetsDir + "meshes/" + file + R"("/>)";
    EXPECT_NEAR(heightAfterTwoSeconds(floatingCubeUrdf(mesh), true), -0.2, 5e-3) << file;
  }
  // Scaled (and mirrored) by <mesh scale>: the 0.6 m side halved.
  const std::string scaled = R"(<mesh filename=")" + kAssetsDir + R"(meshes/box_20x40x60cm.obj" scale="1 -1 0.5"/>)";
  EXPECT_NEAR(heightAfterTwoSeconds(floatingCubeUrdf(scaled), true), 0.15 - 0.5, 5e-3);
}

TEST(MujocoPhysics, RefusesWhatItCannotSimulateNamingTheElement) {
  const std::string dae = R"(<mesh filename=")" + kAssetsDir + R"(meshes/cube_binary.stl"/>)";
  std::string urdf = floatingCubeUrdf(dae);
  // A mesh file that is not there.
  urdf.replace(urdf.find("cube_binary.stl"), 15, "no_such_cube.dae");
  const auto model = urdf::parseURDF(urdf);
  ASSERT_TRUE(model);
  try {
    mjcfFromUrdf(*model, SimSettings{}, {}, "cube.urdf");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("link 'cube'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no_such_cube.dae: cannot read the mesh"), std::string::npos) << e.what();
  }
  const std::string floating = R"(<robot name="f"><link name="world"/>
    <joint name="free" type="floating"><parent link="world"/><child link="b"/></joint>
    <link name="b"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link></robot>)";
  try {
    MujocoPhysics engine;
    engine.init(*parseRobotModel(floating, "f.urdf"), SimSettings{}, {}, "f.urdf");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("joint 'free'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("f.urdf"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace servoloop::sim_mujoco
