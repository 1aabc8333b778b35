// Joint-space physics of BulletWorld on the seed robots and small inline
// robots, checked against analytic solutions and RK4 references.
//
// Error budget used below: Bullet integrates with semi-implicit Euler
// (v += a*dt, then q += v*dt). For smooth motion its position trails the exact
// solution by at most about dt*max|v| (the half-step velocity offset, with
// margin), and its frequency error is O((w*dt)^2), negligible over a few
// seconds at dt = 1 ms. A wrong inertia, damping or gravity changes the
// motion by orders of magnitude more than these bounds.
#include <cmath>
#include <string>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "reference_ode.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/sim_bullet/bullet_world.hpp"

namespace servoloop::sim_bullet {
namespace {

using testing::integrateRk4;

constexpr double kG = 9.81;
const std::string kSeedDir = std::string(SERVOLOOP_SEED_DIR) + "/";

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

WorldSettings noGravity() {
  WorldSettings s;
  s.gravity = Eigen::Vector3d::Zero();
  return s;
}

TEST(BulletWorldJoint, SeedRobotLoadsWithOneMovableJoint) {
  BulletWorld world(*seedWithControl());
  ASSERT_EQ(world.numJoints(), 1u);
  EXPECT_EQ(world.jointNames().at(0), "joint1");
  EXPECT_EQ(world.jointIndex("joint1"), 0u);
  EXPECT_EQ(world.jointType(0), JointType::revolute);
  EXPECT_DOUBLE_EQ(world.jointEffortLimit(0), 10.0);
  EXPECT_TRUE(world.isFixedBase());
  // link1 is glued to world; joint1 sits 1 m above it.
  EXPECT_TRUE(world.linkWorldPosition("link1").isZero(1e-12));
  EXPECT_TRUE(world.linkWorldPosition("link2").isApprox(Eigen::Vector3d(0, 0, 1), 1e-12));
  EXPECT_THROW(world.jointIndex("glue_robot_to_world"), Error);
  EXPECT_EQ(BulletWorld(*seedPendulum()).jointType(0), JointType::continuous);
}

TEST(BulletWorldJoint, UndampedPendulumConservesEnergyAndMatchesRk4) {
  BulletWorld world(*seedPendulum());
  // Link2 points up at q = 0: theta'' = m g d sin(q) / I. Start 0.5 rad from hanging down.
  const double q0 = M_PI - 0.5;
  world.setJointState(0, q0, 0.0);
  const double mgd = kSeedMass * kG * kSeedComDistance;
  const auto energy = [&](double q, double v) { return 0.5 * kSeedInertiaAboutJoint * v * v + mgd * std::cos(q); };
  const double dt = world.timeStep();
  const auto reference =
      integrateRk4([&](double q, double) { return mgd * std::sin(q) / kSeedInertiaAboutJoint; }, q0, 0.0, 3.0, dt);

  // Swing energy above the bottom: mgd (1 - cos 0.5) = 0.60 J, w = sqrt(mgd/I) = 3.74 rad/s.
  // Semi-implicit Euler is symplectic: no drift, an O(dt) oscillation of about
  // dt * w * (swing energy) = 0.002 J. Bound 0.01 J; a 0.04/s link damping would lose > 0.1 J.
  const double e0 = energy(q0, 0.0);
  double max_energy_error = 0.0;
  double max_position_error = 0.0;
  double max_speed = 0.0;
  for (int k = 1; k <= 10000; ++k) {
    world.step();
    const double q = world.jointPosition(0);
    const double v = world.jointVelocity(0);
    max_energy_error = std::max(max_energy_error, std::abs(energy(q, v) - e0));
    if (k < static_cast<int>(reference.size())) {
      max_position_error = std::max(max_position_error, std::abs(q - reference[k].position));
      max_speed = std::max(max_speed, std::abs(reference[k].velocity));
    }
  }
  EXPECT_NEAR(world.time(), 10.0, 1e-9);
  EXPECT_LT(max_energy_error, 0.01);
  EXPECT_LT(max_position_error, dt * max_speed) << "max |v| " << max_speed;
}

TEST(BulletWorldJoint, SeedDampingDecaysVelocityExponentially) {
  // No gravity; b = 1 from the seed URDF: w(t) = w0 exp(-b t / I).
  BulletWorld world(*seedWithControl(), noGravity());
  const double w0 = 0.5;
  world.setJointState(0, 1.0, w0);  // travels w0 I / b = 0.175 rad: stays inside [0, 2]
  const double b = 1.0;
  for (int k = 0; k < 1000; ++k) world.step();
  const double expected = w0 * std::exp(-b * world.time() / kSeedInertiaAboutJoint);
  // Per step the velocity is scaled by (1 - b dt/I) instead of exp(-b dt/I):
  // after n steps a relative error of n (b dt/I)^2 / 2 = 0.4 % at t = 1 s. Bound 1 %.
  EXPECT_NEAR(world.jointVelocity(0), expected, 0.01 * expected);
  const double travelled = world.jointPosition(0) - 1.0;
  const double expected_travel = w0 * kSeedInertiaAboutJoint / b * (1.0 - std::exp(-b * 1.0 / kSeedInertiaAboutJoint));
  EXPECT_NEAR(travelled, expected_travel, 0.01 * expected_travel);
}

TEST(BulletWorldJoint, PrismaticJointFallsFreely) {
  const std::string xml = R"(<robot name="slider"><link name="world"/>
    <joint name="lift" type="prismatic"><parent link="world"/><child link="carriage"/>
      <origin xyz="0 0 0"/><axis xyz="0 0 1"/>
      <limit lower="-1000" upper="1000" effort="100" velocity="100"/></joint>
    <link name="carriage"><inertial><mass value="3"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link></robot>)";
  BulletWorld world(*parseRobotModel(xml, "slider.urdf"));
  ASSERT_EQ(world.jointType(0), JointType::prismatic);
  const double dt = world.timeStep();
  for (int k = 1; k <= 1000; ++k) {
    world.step();
    const double t = world.time();
    // Semi-implicit Euler gives q_n = -g dt^2 n(n+1)/2 = -g t^2/2 - g dt t/2.
    ASSERT_NEAR(world.jointPosition(0), -0.5 * kG * t * t, 0.5 * kG * dt * t + 1e-9) << "t = " << t;
    ASSERT_NEAR(world.jointVelocity(0), -kG * t, 1e-9) << "t = " << t;
  }
  EXPECT_NEAR(world.linkWorldPosition("carriage").z(), world.jointPosition(0), 1e-12);
}

TEST(BulletWorldJoint, CoulombFrictionDeceleratesAtFrictionOverMassAndHolds) {
  // Horizontal slider, m = 3 kg, friction 6 N: decelerates at 2 m/s^2 and stops at t = 0.5 s.
  const std::string xml = R"(<robot name="slider"><link name="world"/>
    <joint name="slide" type="prismatic"><parent link="world"/><child link="carriage"/>
      <axis xyz="1 0 0"/><limit lower="-10" upper="10" effort="100" velocity="10"/>
      <dynamics damping="0" friction="6"/></joint>
    <link name="carriage"><inertial><mass value="3"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link></robot>)";
  BulletWorld world(*parseRobotModel(xml, "friction.urdf"));
  world.setJointState(0, 0.0, 1.0);
  for (int k = 0; k < 250; ++k) world.step();
  // Velocity-level friction removes exactly f dt / m per step while sliding.
  EXPECT_NEAR(world.jointVelocity(0), 1.0 - 2.0 * world.time(), 1e-6);
  for (int k = 0; k < 350; ++k) world.step();
  EXPECT_NEAR(world.jointVelocity(0), 0.0, 1e-9);
  EXPECT_NEAR(world.jointPosition(0), 0.25, 2e-3);  // v0^2 / (2 a), within a step's travel
  // A push below the friction force does not move it; one above accelerates at (F - f) / m.
  const double rest = world.jointPosition(0);
  for (int k = 0; k < 100; ++k) {
    world.setJointEffort(0, 5.0);
    world.step();
  }
  EXPECT_NEAR(world.jointPosition(0), rest, 1e-9);
  for (int k = 0; k < 100; ++k) {
    world.setJointEffort(0, 9.0);
    world.step();
  }
  EXPECT_NEAR(world.jointVelocity(0), (9.0 - 6.0) / 3.0 * 0.1, 1e-6);
}

TEST(BulletWorldJoint, LimitStopsALinkWithoutCollisionGeometry) {
  // Same slider as the free fall test but with its lower stop 0.1 m below.
  const std::string xml = R"(<robot name="slider"><link name="world"/>
    <joint name="lift" type="prismatic"><parent link="world"/><child link="carriage"/>
      <axis xyz="0 0 1"/><limit lower="-0.1" upper="1" effort="100" velocity="100"/></joint>
    <link name="carriage"><inertial><mass value="3"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link></robot>)";
  BulletWorld world(*parseRobotModel(xml, "slider.urdf"));
  for (int k = 0; k < 1000; ++k) world.step();
  EXPECT_NEAR(world.jointPosition(0), -0.1, 1e-3);
  EXPECT_NEAR(world.jointVelocity(0), 0.0, 1e-3);
}

TEST(BulletWorldJoint, LimitHoldsAgainstFullEffort) {
  BulletWorld world(*seedWithControl());
  world.setJointState(0, 1.5, 0.0);
  // +10 N m (the effort limit) plus gravity (m g d sin q = 4.5 N m near q = 2)
  // push into the upper stop at 2 rad; without the stop the link would pass pi.
  double max_position = 0.0;
  for (int k = 0; k < 2000; ++k) {
    world.setJointEffort(0, 10.0);
    world.step();
    max_position = std::max(max_position, world.jointPosition(0));
  }
  constexpr double kPenetrationTolerance = 0.01;  // rad: the stop's position correction is soft per step
  EXPECT_LT(max_position, 2.0 + kPenetrationTolerance);
  EXPECT_NEAR(world.jointPosition(0), 2.0, kPenetrationTolerance);
  EXPECT_NEAR(world.jointVelocity(0), 0.0, 0.01);
}

TEST(BulletWorldJoint, EffortIsAppliedAsGivenBeyondTheUrdfLimit) {
  // Limits are SimRobotHW's (URDF + YAML, which may be looser than the URDF);
  // the world must not clamp a second time at <limit effort> = 10 N m.
  BulletWorld world(*seedWithControl(), noGravity());
  world.setJointState(0, 0.2, 0.0);
  for (int k = 0; k < 100; ++k) {
    world.setJointEffort(0, 20.0);  // 2x the URDF limit
    world.step();
    ASSERT_EQ(world.jointAppliedEffort(0), 20.0);
  }
  // 20 N m damped by -1 * v: v(t) = (tau/b)(1 - exp(-b t / I)) = 4.97 rad/s at
  // 0.1 s (2.49 if clamped at 10). Discretisation error of the damping: well under 1 %.
  const double expected = 20.0 * (1.0 - std::exp(-0.1 / kSeedInertiaAboutJoint));
  EXPECT_NEAR(world.jointVelocity(0), expected, 0.01 * expected);
}

TEST(BulletWorldJoint, EffortActsForOneStepOnly) {
  BulletWorld world(*seedPendulum(), noGravity());
  world.setJointEffort(0, 3.5);
  world.step();
  const double v1 = world.jointVelocity(0);
  EXPECT_NEAR(v1, 3.5 / kSeedInertiaAboutJoint * world.timeStep(), 1e-9);
  world.step();
  EXPECT_NEAR(world.jointVelocity(0), v1, 1e-12);
}

TEST(BulletWorldJoint, OffDiagonalRotatedInertiaSwingsAsTheProjectedTensorSays) {
  // Inertial frame rotated and tensor full: only a^T R I R^T a + m |c_perp|^2
  // about the joint axis a = y matters for a single hinge.
  const double m = 1.5;
  const Eigen::Vector3d c(0.1, 0.05, -0.2);
  const Eigen::Vector3d rpy(0.4, -0.3, 0.7);
  Eigen::Matrix3d inertia;
  inertia << 0.20, 0.03, 0.02,  //
      0.03, 0.12, -0.04,        //
      0.02, -0.04, 0.15;
  // A physically possible body: positive principal moments with A + B >= C
  // for every ordering (MuJoCo refuses anything else; a real body cannot have it).
  const Eigen::Vector3d moments = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia).eigenvalues();
  ASSERT_GT(moments.minCoeff(), 0.0);
  ASSERT_GE(moments[0] + moments[1], moments[2]) << "principal moments " << moments.transpose();
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

  BulletWorld world(*parseRobotModel(xml, "tumbler.urdf"));
  // Gravity torque about y of the COM rotated by q about y: m g (cx cos q + cz sin q).
  const auto acceleration = [&](double q, double) {
    return m * kG * (c.x() * std::cos(q) + c.z() * std::sin(q)) / inertia_about_axis;
  };
  const double q0 = 1.0;
  world.setJointState(0, q0, 0.0);
  const double dt = world.timeStep();
  const auto reference = integrateRk4(acceleration, q0, 0.0, 3.0, dt);
  double max_error = 0.0, max_speed = 0.0;
  for (std::size_t k = 1; k < reference.size(); ++k) {
    world.step();
    max_error = std::max(max_error, std::abs(world.jointPosition(0) - reference[k].position));
    max_speed = std::max(max_speed, std::abs(reference[k].velocity));
  }
  EXPECT_LT(max_error, dt * max_speed) << "max |v| " << max_speed;
}

TEST(BulletWorldJoint, VelocityMotorReachesTargetWithinEffortLimit) {
  BulletWorld world(*seedWithControl());
  world.setJointState(0, 0.5, 0.0);
  for (int k = 0; k < 300; ++k) {
    world.setJointVelocityTarget(0, 0.3);
    world.step();
  }
  EXPECT_NEAR(world.jointVelocity(0), 0.3, 1e-3);
}

TEST(BulletWorldJoint, PositionMotorHoldsTargetAgainstGravity) {
  BulletWorld world(*seedWithControl());
  world.setJointState(0, 0.5, 0.0);
  world.setJointPositionTarget(0, 1.2);
  for (int k = 0; k < 1000; ++k) world.step();
  EXPECT_NEAR(world.jointPosition(0), 1.2, 1e-3);
  EXPECT_NEAR(world.jointVelocity(0), 0.0, 1e-2);
}

TEST(BulletWorldJoint, HiddenBulletDefaultsAreOff) {
  EXPECT_TRUE(BulletWorld::usesDoublePrecision());
  BulletWorld world(*seedPendulum(), noGravity());
  EXPECT_EQ(world.linkLinearDamping(), 0.0);
  EXPECT_EQ(world.linkAngularDamping(), 0.0);
  EXPECT_GT(world.maxCoordinateVelocity(), 1e4);
  // Bullet's default would clamp at 100 rad/s and damp by 0.04/s.
  world.setJointState(0, 0.0, 200.0);
  for (int k = 0; k < 500; ++k) world.step();
  EXPECT_NEAR(world.jointVelocity(0), 200.0, 1e-6);
  EXPECT_NEAR(world.jointPosition(0), 200.0 * world.time(), 1e-6);
}

TEST(BulletWorldJoint, ResetRestoresInitialState) {
  BulletWorld world(*seedWithControl());
  world.setJointState(0, 1.0, 0.3);
  world.setJointVelocityTarget(0, 0.4);
  for (int k = 0; k < 50; ++k) world.step();
  world.reset();
  EXPECT_EQ(world.time(), 0.0);
  EXPECT_EQ(world.jointPosition(0), 0.0);
  EXPECT_EQ(world.jointVelocity(0), 0.0);
  // Back in effort mode with no effort, in zero gravity the joint stays still.
  BulletWorld still(*seedWithControl(), noGravity());
  still.setJointVelocityTarget(0, 0.4);
  still.step();
  still.reset();
  still.setJointState(0, 1.0, 0.0);
  for (int k = 0; k < 50; ++k) still.step();
  EXPECT_NEAR(still.jointPosition(0), 1.0, 1e-12);
}

TEST(BulletWorldJoint, RejectsBadSettingsAndJoints) {
  WorldSettings bad;
  bad.time_step_s = 0.0;
  EXPECT_THROW(BulletWorld(*seedPendulum(), bad), ConfigError);
  const std::string floating = R"(<robot name="f"><link name="world"/>
    <joint name="free" type="floating"><parent link="world"/><child link="b"/></joint>
    <link name="b"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link></robot>)";
  try {
    BulletWorld world(*parseRobotModel(floating, "f.urdf"));
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("joint 'free'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace servoloop::sim_bullet
