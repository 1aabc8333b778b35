// Reflected rotor inertia in BulletWorld (WorldSettings::reflected_rotor_inertia):
// added to the child body's inertia about the joint axis. Checked against
// hand calculations of the joint-space inertia: one step of an effort τ from
// rest without gravity gives exactly v = dt·M⁻¹·τ (semi-implicit Euler), so
// M is read off to rounding; and a swing against an RK4 reference.
#include <cmath>
#include <string>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "reference_ode.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/sim_bullet/bullet_world.hpp"

namespace servoloop::sim_bullet {
namespace {

constexpr double kG = 9.81;

std::shared_ptr<const urdf::ModelInterface> seedPendulum() {  // continuous joint1, no damping
  return loadRobotModelFile(std::string(SERVOLOOP_SEED_DIR) + "/minimal_robot_description.urdf");
}
constexpr double kSeedInertia = 0.35;  // kg m², link2 about joint1
constexpr double kSeedGravityTorque = 1.0 * kG * 0.5;

WorldSettings withRotorInertia(const std::map<std::string, double>& rotor, bool gravity) {
  WorldSettings s;
  if (!gravity) s.gravity = Eigen::Vector3d::Zero();
  s.reflected_rotor_inertia = rotor;
  return s;
}

// Velocity after one step of `effort` on `joint` from rest: dt·(M⁻¹)_jj·effort.
double oneStepVelocity(BulletWorld& world, std::size_t joint, double effort) {
  world.setJointEffort(joint, effort);
  world.step();
  return world.jointVelocity(joint);
}

TEST(BulletWorldRotorInertia, SingleJointFeelsExactlyTheAddedInertia) {
  constexpr double kRotor = 0.05;  // e.g. J = 2e-5 kg m² behind a 50:1 gear
  BulletWorld world(*seedPendulum(), withRotorInertia({{"joint1", kRotor}}, false));
  EXPECT_DOUBLE_EQ(world.jointRotorInertia(0), kRotor);
  // The URDF mass properties are reported unchanged.
  EXPECT_NEAR(world.bodyMassProperties("link2").inertia(1, 1), 0.1, 1e-12);
  const double v = oneStepVelocity(world, 0, 3.5);
  EXPECT_NEAR(v, 3.5 * world.timeStep() / (kSeedInertia + kRotor), 1e-12);
  // Without it: 3.5 dt / 0.35, 14 % faster.
  BulletWorld plain(*seedPendulum(), withRotorInertia({}, false));
  EXPECT_EQ(plain.jointRotorInertia(0), 0.0);
  EXPECT_NEAR(oneStepVelocity(plain, 0, 3.5), 3.5 * plain.timeStep() / kSeedInertia, 1e-12);
}

TEST(BulletWorldRotorInertia, PendulumWithRotorInertiaSwingsAsRk4WithTheSummedInertia) {
  constexpr double kRotor = 0.1;
  BulletWorld world(*seedPendulum(), withRotorInertia({{"joint1", kRotor}}, true));
  const double q0 = M_PI - 0.5;
  world.setJointState(0, q0, 0.0);
  const double dt = world.timeStep();
  const auto swing = [&](double inertia) {
    return testing::integrateRk4([=](double q, double) { return kSeedGravityTorque * std::sin(q) / inertia; }, q0,
                                 0.0, 3.0, dt);
  };
  const auto reference = swing(kSeedInertia + kRotor);
  const auto without_rotor = swing(kSeedInertia);
  double max_error = 0.0, max_speed = 0.0, max_rotor_effect = 0.0;
  for (std::size_t k = 1; k < reference.size(); ++k) {
    world.step();
    max_error = std::max(max_error, std::abs(world.jointPosition(0) - reference[k].position));
    max_speed = std::max(max_speed, std::abs(reference[k].velocity));
    max_rotor_effect = std::max(max_rotor_effect, std::abs(without_rotor[k].position - reference[k].position));
  }
  // Semi-implicit Euler's bound (see bullet_world_joint_test.cpp): dt·max|v|.
  const double bound = dt * max_speed;
  EXPECT_LT(max_error, bound) << "max |v| " << max_speed;
  ASSERT_GT(max_rotor_effect, 20.0 * bound) << "the case must tell the rotor inertia apart";
}

TEST(BulletWorldRotorInertia, AddsAboutATiltedAxisOfARotatedFullTensor) {
  // Axis (0, 0.6, 0.8), inertial frame rotated, full tensor: the joint feels
  // aᵀ·R·I·Rᵀ·a + m·|c⊥|² + k (c⊥: the COM offset perpendicular to a).
  const double m = 1.5, k = 0.07;
  const Eigen::Vector3d c(0.1, 0.05, -0.2), a(0.0, 0.6, 0.8), rpy(0.4, -0.3, 0.7);
  Eigen::Matrix3d inertia;
  inertia << 0.20, 0.03, 0.02,  //
      0.03, 0.12, -0.04,        //
      0.02, -0.04, 0.15;
  const std::string xml = R"(<robot name="tilted"><link name="world"/>
    <joint name="hinge" type="revolute"><parent link="world"/><child link="body"/>
      <axis xyz="0 0.6 0.8"/><limit lower="-3" upper="3" effort="100" velocity="10"/></joint>
    <link name="body"><inertial><origin xyz="0.1 0.05 -0.2" rpy="0.4 -0.3 0.7"/><mass value="1.5"/>
      <inertia ixx="0.20" ixy="0.03" ixz="0.02" iyy="0.12" iyz="-0.04" izz="0.15"/></inertial></link></robot>)";
  const Eigen::Matrix3d r = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  const Eigen::Vector3d c_perpendicular = c - c.dot(a) * a;
  const double axis_inertia = a.dot(r * inertia * r.transpose() * a) + m * c_perpendicular.squaredNorm();

  BulletWorld world(*parseRobotModel(xml, "tilted.urdf"), withRotorInertia({{"hinge", k}}, false));
  EXPECT_NEAR(oneStepVelocity(world, 0, 2.0), 2.0 * world.timeStep() / (axis_inertia + k), 1e-12);
}

// two_joint_arm.urdf (tests/cross_engine): both axes y (parallel), so rotor
// inertia k added to the forearm about the elbow axis is felt by the shoulder
// as well: M + k·[[1, 1], [1, 1]] instead of true armature's M + k·[[0, 0], [0, 1]].
// On the shoulder (parent: the fixed base) it is exact: M + k·[[1, 0], [0, 0]].
Eigen::Matrix2d armMassMatrix(double q2) {
  constexpr double kL1 = 0.5, kC1 = 0.25, kM1 = 1.5, kI1 = 0.02, kC2 = 0.2, kM2 = 1.0, kI2 = 0.01;
  Eigen::Matrix2d mass;
  mass(0, 0) = kI1 + kI2 + kM1 * kC1 * kC1 + kM2 * (kL1 * kL1 + kC2 * kC2 + 2.0 * kL1 * kC2 * std::cos(q2));
  mass(0, 1) = mass(1, 0) = kI2 + kM2 * (kC2 * kC2 + kL1 * kC2 * std::cos(q2));
  mass(1, 1) = kI2 + kM2 * kC2 * kC2;
  return mass;
}

// Bullet's joint-space inverse inertia at (0, q2), column by column.
Eigen::Matrix2d measuredInverseMass(const std::map<std::string, double>& rotor, double q2) {
  const auto model = loadRobotModelFile(std::string(SERVOLOOP_SOURCE_DIR) + "/tests/cross_engine/two_joint_arm.urdf");
  Eigen::Matrix2d inverse;
  for (std::size_t column = 0; column < 2; ++column) {
    BulletWorld world(*model, withRotorInertia(rotor, false));
    EXPECT_EQ(world.jointNames(), (std::vector<std::string>{"shoulder", "elbow"}));
    world.setJointState(1, q2, 0.0);
    world.setJointEffort(column, 1.0);
    world.step();
    for (std::size_t row = 0; row < 2; ++row) inverse(row, column) = world.jointVelocity(row) / world.timeStep();
  }
  return inverse;
}

TEST(BulletWorldRotorInertia, OnAChainTheParentJointFeelsTheChildRotorThroughParallelAxes) {
  constexpr double kQ2 = 0.5, kRotor = 0.05;
  const Eigen::Matrix2d mass = armMassMatrix(kQ2);
  EXPECT_TRUE(measuredInverseMass({}, kQ2).isApprox(mass.inverse(), 1e-10)) << "without rotor inertia";

  Eigen::Matrix2d shoulder_rotor = mass;
  shoulder_rotor(0, 0) += kRotor;
  EXPECT_TRUE(measuredInverseMass({{"shoulder", kRotor}}, kQ2).isApprox(shoulder_rotor.inverse(), 1e-10))
      << "the root joint's rotor inertia is exact";

  Eigen::Matrix2d elbow_rotor_coupled = mass;
  elbow_rotor_coupled += kRotor * Eigen::Matrix2d::Ones();
  Eigen::Matrix2d elbow_armature = mass;
  elbow_armature(1, 1) += kRotor;
  const Eigen::Matrix2d measured = measuredInverseMass({{"elbow", kRotor}}, kQ2);
  EXPECT_TRUE(measured.isApprox(elbow_rotor_coupled.inverse(), 1e-10)) << measured;
  EXPECT_FALSE(measured.isApprox(elbow_armature.inverse(), 1e-3)) << "the documented approximation";
}

TEST(BulletWorldRotorInertia, RejectsPrismaticUnknownAndNegative) {
  const std::string slider = R"(<robot name="slider"><link name="world"/>
    <joint name="slide" type="prismatic"><parent link="world"/><child link="carriage"/>
      <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="100" velocity="10"/></joint>
    <link name="carriage"><inertial><mass value="3"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link></robot>)";
  const auto expect_error = [](const urdf::ModelInterface& model, const std::map<std::string, double>& rotor,
                               const std::string& expected) {
    try {
      BulletWorld world(model, withRotorInertia(rotor, true));
      FAIL() << "expected ConfigError containing '" << expected << "'";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  expect_error(*parseRobotModel(slider, "slider.urdf"), {{"slide", 0.1}}, "joint 'slide': the Bullet world models");
  expect_error(*seedPendulum(), {{"joint9", 0.1}}, "joint 'joint9': the robot has no");
  expect_error(*seedPendulum(), {{"joint1", -0.1}}, "must be a finite number >= 0");
}

}  // namespace
}  // namespace servoloop::sim_bullet
