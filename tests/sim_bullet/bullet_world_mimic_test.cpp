// <mimic>: the physics holds q_follower = multiplier·q_drive + offset, and the
// coupled pair moves as one body of the inertia virtual work gives.
//
// tests/assets/features/mimic_pair.urdf: two wheels, izz = 0.01 kg m² each,
// multiplier −0.5, offset 0.1. A torque τ on the drive alone accelerates the
// pair with I_eff = I_drive + multiplier²·I_follower = 0.0125 kg m², so from
// rest q_drive(t) = τ t² / (2 I_eff): 0.8 rad after 1 s with τ = 0.02 N m
// (1.0 rad if the follower were not coupled).
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/sim_bullet/bullet_world.hpp"

namespace servoloop::sim_bullet {
namespace {

const std::string kAssets = std::string(SERVOLOOP_SOURCE_DIR) + "/tests/assets/features/";

TEST(BulletWorldMimic, FollowerTracksItsLeaderAndAddsItsInertia) {
  const auto model = loadRobotModelFile(kAssets + "mimic_pair.urdf");
  BulletWorld world(*model);
  const std::size_t drive = world.jointIndex("drive");
  const std::size_t follower = world.jointIndex("follower");
  world.setJointState(follower, 0.1, 0.0);  // start on the mimic relation

  constexpr double kTorque = 0.02, kInertia = 0.01 + 0.25 * 0.01;
  double worst = 0.0;
  for (int step = 0; step < 1000; ++step) {
    world.setJointEffort(drive, kTorque);
    world.step();
    const double expected = -0.5 * world.jointPosition(drive) + 0.1;
    worst = std::max(worst, std::abs(world.jointPosition(follower) - expected));
  }
  // Semi-implicit Euler trails the exact q by at most dt·max|q̇| = 1.6e-3 rad
  // (q̇ ≤ 1.6 rad/s); the coupling's error is a small share of one step's motion.
  EXPECT_NEAR(world.jointPosition(drive), kTorque / (2 * kInertia), 2e-3);
  EXPECT_LT(worst, 1e-3) << "largest |q_follower − (−0.5 q_drive + 0.1)|";
}

TEST(BulletWorldMimic, UnknownLeaderIsNamed) {
  std::string urdf = R"(<robot name="r"><link name="world"/><link name="a"><inertial><mass value="1"/>
    <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
    <joint name="j" type="continuous"><parent link="world"/><child link="a"/><mimic joint="ghost"/></joint></robot>)";
  try {
    BulletWorld world(*parseRobotModel(urdf, "r.urdf"));
    ADD_FAILURE() << "expected an error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("joint 'j' <mimic joint=\"ghost\">"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace servoloop::sim_bullet
