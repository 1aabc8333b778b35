// Real robots' features on MuJoCo.
//
// <mimic>: a joint equality holds q_follower = multiplier·q_drive +
// offset, and the pair moves with the inertia virtual work gives (the same
// case as tests/sim_bullet/bullet_world_mimic_test.cpp, worked out there):
// I_eff = 0.01 + 0.25·0.01 = 0.0125 kg m², q_drive(1 s) = 0.02 / (2 I_eff) = 0.8 rad.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "log_capture.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/sim_mujoco/mjcf_from_urdf.hpp"
#include "servoloop/sim_mujoco/mujoco_physics.hpp"

namespace servoloop::sim_mujoco {
namespace {

const std::string kAssets = std::string(SERVOLOOP_SOURCE_DIR) + "/tests/assets/features/";

TEST(MujocoMimic, FollowerTracksItsLeaderAndAddsItsInertia) {
  const auto model = loadRobotModelFile(kAssets + "mimic_pair.urdf");
  sim_common::SimSettings settings;
  std::vector<sim_common::EngineJointConfig> joints(2);
  joints[0].name = "drive";
  joints[1].name = "follower";
  joints[1].initial_position = 0.1;  // start on the mimic relation
  MujocoPhysics engine;
  engine.init(*model, settings, joints, "mimic_pair.urdf");

  constexpr double kTorque = 0.02, kInertia = 0.01 + 0.25 * 0.01;
  const std::vector<sim_common::AppliedJointCommand> commands{
      {sim_common::JointCommandMode::effort, kTorque}, {sim_common::JointCommandMode::none, 0.0}};
  double worst = 0.0;
  for (int step = 0; step < 1000; ++step) {
    engine.applyJointCommands(commands);
    engine.step();
    worst = std::max(worst, std::abs(engine.jointPosition(1) - (-0.5 * engine.jointPosition(0) + 0.1)));
  }
  // RK4 at 1 ms is far more accurate than the bound; the equality is a soft
  // constraint with a two-step time constant, so it lags by about two steps
  // of the relative motion: 2·dt·0.5·max|q̇| = 1.6e-3 rad.
  EXPECT_NEAR(engine.jointPosition(0), kTorque / (2 * kInertia), 4e-3);
  EXPECT_LT(worst, 2e-3) << "largest |q_follower − (−0.5 q_drive + 0.1)|";
}

TEST(MujocoMimic, UnknownLeaderIsNamed) {
  const std::string urdf = R"(<robot name="r"><link name="world"/><link name="a"><inertial><mass value="1"/>
    <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
    <joint name="j" type="continuous"><parent link="world"/><child link="a"/><mimic joint="ghost"/></joint></robot>)";
  // The loader refuses it before any backend sees it, naming the joint.
  try {
    parseRobotModel(urdf, "r.urdf");
    ADD_FAILURE() << "expected an error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("r.urdf: joint 'j' <mimic joint=\"ghost\">: no joint 'ghost' in this robot"),
              std::string::npos)
        << e.what();
  }
}

// Principal moments a hair off A + B >= C (rounded values, as in PR2's
// description; servoloop's loader accepts them within 1e-9 relative) load with
// MuJoCo balancing them and one warning naming the link.
TEST(MujocoInertia, RoundedMomentsBreakingTheTriangleByAHairAreBalanced) {
  const std::string urdf = R"(<robot name="r"><link name="world"/><link name="plate"><inertial><mass value="1"/>
    <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.20000000000002"/></inertial></link>
    <joint name="j" type="continuous"><parent link="world"/><child link="plate"/><axis xyz="0 0 1"/></joint></robot>)";
  const auto model = parseRobotModel(urdf, "r.urdf");
  test::LogCapture log;
  std::vector<sim_common::EngineJointConfig> joints(1);
  joints[0].name = "j";
  MujocoPhysics engine;
  EXPECT_NO_THROW(engine.init(*model, sim_common::SimSettings{}, joints, "r.urdf"));
  EXPECT_EQ(log.count("link 'plate': principal moments"), 1u) << log.text();
  EXPECT_NE(mjcfFromUrdf(*model, sim_common::SimSettings{}, {}, "r.urdf").find("balanceinertia=\"true\""),
            std::string::npos);
}

}  // namespace
}  // namespace servoloop::sim_mujoco
