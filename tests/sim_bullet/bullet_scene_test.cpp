// Robots and objects in one Bullet scene, touching each other, against
// closed-form references: a sliding box stops after v²/(2μg), a box rests on
// a table, a slider pushes a box, two arms stop in contact; and the scene's
// own guarantees: members apart behave as alone, reruns are bit-identical,
// a member removed leaves the others running.
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/sim_bullet/bullet_scene.hpp"
#include "servoloop/sim_bullet/bullet_world.hpp"

namespace servoloop::sim_bullet {
namespace {

constexpr double kG = 9.81;

// A free box of side `side` m and mass `mass` kg: one link, no joint (an object).
std::string boxUrdf(const std::string& name, double side, double mass) {
  const double i = mass * side * side / 6.0;
  const std::string s = std::to_string(side);
  return "<robot name=\"" + name + "\"><link name=\"box\"><inertial><mass value=\"" + std::to_string(mass) +
         "\"/><inertia ixx=\"" + std::to_string(i) + "\" ixy=\"0\" ixz=\"0\" iyy=\"" + std::to_string(i) +
         "\" iyz=\"0\" izz=\"" + std::to_string(i) + "\"/></inertial><collision><geometry><box size=\"" + s + " " +
         s + " " + s + "\"/></geometry></collision></link></robot>";
}

// A table: a fixed 1 m × 1 m top, 0.1 m thick, its surface at z = 0.5.
const char* kTableUrdf = R"(<robot name="table"><link name="world"/>
  <joint name="legs" type="fixed"><parent link="world"/><child link="top"/><origin xyz="0 0 0.45"/></joint>
  <link name="top"><inertial><mass value="20"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <collision><geometry><box size="1 1 0.1"/></geometry></collision></link></robot>)";

// A paddle on a rail along x: a fixed base and a prismatic joint, the
// paddle a 0.05 m (x) × 0.4 m × 0.2 m plate whose centre is 0.12 m above the
// ground (clear of it: the rail carries it).
const char* kPusherUrdf = R"(<robot name="pusher"><link name="world"/>
  <joint name="rail" type="prismatic"><parent link="world"/><child link="paddle"/>
    <origin xyz="0 0 0.12"/><axis xyz="1 0 0"/><limit lower="-5" upper="5" effort="1000" velocity="10"/></joint>
  <link name="paddle"><inertial><mass value="5"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
    <collision><geometry><box size="0.05 0.4 0.2"/></geometry></collision></link></robot>)";

// An arm turning about z: a 1 m bar (0.1 m × 0.1 m section) from the hinge
// along +x, at height 0.5 m, placed with the base pose.
const char* kSweepArmUrdf = R"(<robot name="arm"><link name="base"><inertial><mass value="1"/>
    <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <joint name="hinge" type="continuous"><parent link="base"/><child link="bar"/>
    <origin xyz="0 0 0.5"/><axis xyz="0 0 1"/><limit effort="50" velocity="10"/></joint>
  <link name="bar"><inertial><origin xyz="0.5 0 0"/><mass value="2"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.17" iyz="0" izz="0.17"/></inertial>
    <collision><origin xyz="0.5 0 0"/><geometry><box size="1 0.1 0.1"/></geometry></collision></link></robot>)";

// A pendulum hanging from a fixed hinge at z = 2 (no collision geometry).
const char* kPendulumUrdf = R"(<robot name="pendulum"><link name="world"/>
  <joint name="hinge" type="continuous"><parent link="world"/><child link="rod"/>
    <origin xyz="0 0 2"/><axis xyz="0 1 0"/></joint>
  <link name="rod"><inertial><origin xyz="0 0 -0.5"/><mass value="1"/>
    <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.001"/></inertial></link></robot>)";

WorldSettings memberSettings(const SceneSettings& scene) {
  WorldSettings settings;
  settings.gravity = scene.gravity;
  settings.time_step_s = scene.time_step_s;
  settings.ground_plane = scene.ground_plane;
  return settings;
}

WorldSettings placedAt(const SceneSettings& scene, const Eigen::Vector3d& position,
                       double yaw = 0.0) {
  WorldSettings settings = memberSettings(scene);
  settings.initial_base_position = position;
  settings.initial_base_orientation = Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
  return settings;
}

void stepFor(BulletScene& scene, double seconds) {
  const auto steps = static_cast<int>(std::llround(seconds / scene.timeStep()));
  for (int k = 0; k < steps; ++k) scene.step();
}

// Reference: a block sliding on a plane with Coulomb friction μ decelerates
// at μg and stops after v²/(2μg). Box-box contact friction is the smaller
// coefficient (the ground's is unbounded), so the box's own μ is the one.
TEST(BulletScene, SlidingBoxStopsAfterTheCoulombDistance) {
  const SceneSettings scene_settings{{0, 0, -kG}, 0.001, true};
  for (const double mu : {0.3, 0.6}) {
    BulletScene scene(scene_settings);
    WorldSettings settings = placedAt(scene_settings, {0, 0, 0.1});
    settings.link_friction["box"] = mu;
    BulletWorld box(*parseRobotModel(boxUrdf("crate", 0.2, 2.0), "crate.urdf"), settings, scene);
    stepFor(scene, 0.5);  // settles on the ground
    BaseState state = box.baseState();
    ASSERT_NEAR(state.position.z(), 0.1, 2e-3);
    const double v = 1.5;
    const double x0 = state.position.x();
    state.linear_velocity = Eigen::Vector3d(v, 0, 0);
    box.setBaseState(state);
    int steps = 0;
    while (box.baseState().linear_velocity.x() > 1e-4 && steps < 5000) {
      scene.step();
      ++steps;
    }
    const double expected = v * v / (2.0 * mu * kG);
    const double travelled = box.baseState().position.x() - x0;
    EXPECT_NEAR(travelled, expected, 0.03 * expected) << "mu " << mu;
    EXPECT_NEAR(steps * 0.001, v / (mu * kG), 0.03 * v / (mu * kG)) << "mu " << mu;
    EXPECT_NEAR(box.baseState().position.y(), 0.0, 1e-3);
  }
}

TEST(BulletScene, BoxRestingOnAStaticTableDriftsLessThanAMillimetre) {
  const SceneSettings scene_settings{{0, 0, -kG}, 0.001, true};
  BulletScene scene(scene_settings);
  BulletWorld table(*parseRobotModel(kTableUrdf, "table.urdf"), memberSettings(scene_settings), scene);
  BulletWorld box(*parseRobotModel(boxUrdf("part", 0.05, 0.1), "part.urdf"),
                  placedAt(scene_settings, {0.1, -0.2, 0.525}), scene);
  ASSERT_TRUE(table.isFixedBase());
  ASSERT_FALSE(box.isFixedBase());
  stepFor(scene, 0.2);
  const Eigen::Vector3d settled = box.baseState().position;
  EXPECT_NEAR(settled.z(), 0.525, 2e-3) << "the box rests on the table top, not on the ground";
  stepFor(scene, 10.0);
  EXPECT_LT((box.baseState().position - settled).norm(), 1e-3);
  EXPECT_LT(box.baseState().linear_velocity.norm(), 1e-3);
}

TEST(BulletScene, SliderPushesAFreeBoxAlongItsPath) {
  const SceneSettings scene_settings{{0, 0, -kG}, 0.001, true};
  BulletScene scene(scene_settings);
  // A slick paddle (μ = 0): with friction on its face too, how much of the
  // box's weight it presses down is statically indeterminate.
  WorldSettings pusher_settings = memberSettings(scene_settings);
  pusher_settings.link_friction["paddle"] = 0.0;
  BulletWorld pusher(*parseRobotModel(kPusherUrdf, "pusher.urdf"), pusher_settings, scene);
  // The paddle's front face at x = 0.025; the 0.2 m box 0.1 m ahead of it.
  const double mu = 0.5;
  WorldSettings box_settings = placedAt(scene_settings, {0.225, 0, 0.1});
  box_settings.link_friction["box"] = mu;
  BulletWorld box(*parseRobotModel(boxUrdf("crate", 0.2, 1.0), "crate.urdf"), box_settings, scene);
  stepFor(scene, 0.3);
  const Eigen::Vector3d start = box.baseState().position;
  const double speed = 0.25;
  double pushing_effort = 0.0;  // mean over the last 2 s
  for (int k = 0; k < 6000; ++k) {  // 6 s at 0.25 m/s: the paddle moves 1.5 m
    pusher.setJointVelocityTarget(0, speed);
    scene.step();
    if (k >= 4000) pushing_effort += pusher.jointAppliedEffort(0) / 2000.0;
  }
  const Eigen::Vector3d end = box.baseState().position;
  const double paddle_front = pusher.jointPosition(0) + 0.025;
  EXPECT_NEAR(pusher.jointPosition(0), 1.5, 0.01);
  // The box was pushed 1.4 m (1.5 m less the 0.1 m gap), its back face on the paddle.
  EXPECT_NEAR(end.x() - start.x(), 1.4, 0.01);
  EXPECT_NEAR(end.x() - 0.1, paddle_front, 5e-3);
  EXPECT_NEAR(end.y(), start.y(), 0.01);
  // At constant speed the paddle pushes against the box's sliding friction μmg.
  EXPECT_NEAR(pushing_effort, mu * 1.0 * kG, 0.03 * mu * kG);
}

TEST(BulletScene, ArmsSweptIntoEachOtherStopInContact) {
  const SceneSettings scene_settings{{0, 0, -kG}, 0.001, false};
  BulletScene scene(scene_settings);
  // Hinges 1.5 m apart on x, both bars pointing along +y at the start; the
  // left one turns clockwise (towards +x), the right one counter-clockwise
  // (towards −x): unhindered they would overlap from ~48° on.
  WorldSettings left_settings = placedAt(scene_settings, {0, 0, 0}, std::numbers::pi / 2);
  left_settings.fixed_base = FixedBase::fixed;
  WorldSettings right_settings = placedAt(scene_settings, {1.5, 0, 0}, std::numbers::pi / 2);
  right_settings.fixed_base = FixedBase::fixed;
  BulletWorld left(*parseRobotModel(kSweepArmUrdf, "left.urdf"), left_settings, scene);
  BulletWorld right(*parseRobotModel(kSweepArmUrdf, "right.urdf"), right_settings, scene);
  for (int k = 0; k < 3000; ++k) {
    left.setJointVelocityTarget(0, -1.0);
    right.setJointVelocityTarget(0, 1.0);
    scene.step();
  }
  // Where they meet: the bars' tips cross the mid line x = 0.75 when cos(90° − θ)
  // reaches 0.75 (edges 0.05 m off the centre line): they stop short of 90°.
  const double left_turned = -left.jointPosition(0);
  const double right_turned = right.jointPosition(0);
  EXPECT_GT(left_turned, 0.5);
  EXPECT_GT(right_turned, 0.5);
  EXPECT_LT(left_turned, std::numbers::pi / 2 - 0.3) << "the left arm swept through the right one";
  EXPECT_LT(right_turned, std::numbers::pi / 2 - 0.3) << "the right arm swept through the left one";
  EXPECT_NEAR(left_turned, right_turned, 0.05) << "equal arms pushing equally meet in the middle";
  EXPECT_LT(std::abs(left.jointVelocity(0)), 0.01);
  // Both motors push at their effort limit against each other.
  EXPECT_NEAR(std::abs(left.jointAppliedEffort(0)), 50.0, 1.0);
}

TEST(BulletScene, MembersApartMoveExactlyAsEachAlone) {
  const SceneSettings scene_settings{{0, 0, -kG}, 0.001, true};
  const auto model = parseRobotModel(kPendulumUrdf, "pendulum.urdf");
  BulletWorld alone(*model, memberSettings(scene_settings));
  BulletScene scene(scene_settings);
  BulletWorld first(*model, memberSettings(scene_settings), scene);
  BulletWorld second(*model, placedAt(scene_settings, {5, 0, 0}), scene);
  alone.setJointState(0, 0.7, 0.0);
  first.setJointState(0, 0.7, 0.0);
  second.setJointState(0, -0.3, 0.0);
  for (int k = 0; k < 2000; ++k) {
    alone.setJointEffort(0, 0.5);
    first.setJointEffort(0, 0.5);
    alone.step();
    scene.step();
    ASSERT_EQ(first.jointPosition(0), alone.jointPosition(0)) << "step " << k;
  }
  EXPECT_EQ(first.time(), alone.time());
  EXPECT_EQ(scene.time(), alone.time());
}

std::vector<double> pushRun() {
  const SceneSettings scene_settings{{0, 0, -kG}, 0.001, true};
  BulletScene scene(scene_settings);
  BulletWorld pusher(*parseRobotModel(kPusherUrdf, "pusher.urdf"), memberSettings(scene_settings), scene);
  std::vector<std::unique_ptr<BulletWorld>> boxes;
  for (int i = 0; i < 3; ++i) {
    boxes.push_back(std::make_unique<BulletWorld>(*parseRobotModel(boxUrdf("b", 0.2, 1.0), "b.urdf"),
                                                  placedAt(scene_settings, {0.2 + 0.21 * i, 0.05 * i, 0.1}), scene));
  }
  std::vector<double> trace;
  for (int k = 0; k < 2000; ++k) {
    pusher.setJointEffort(0, 40.0);
    scene.step();
    for (const auto& box : boxes) {
      const BaseState s = box->baseState();
      trace.insert(trace.end(), {s.position.x(), s.position.y(), s.position.z(), s.orientation.w()});
    }
  }
  return trace;
}

TEST(BulletScene, RerunsAreBitIdentical) {
  const std::vector<double> first = pushRun();
  const std::vector<double> second = pushRun();
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t i = 0; i < first.size(); ++i) ASSERT_EQ(first[i], second[i]) << "value " << i;
  EXPECT_GT(first[first.size() - 4], 0.6) << "the pusher moved the first box";
}

TEST(BulletScene, RemovingAMemberLeavesTheOthersRunningUnchanged) {
  const SceneSettings scene_settings{{0, 0, -kG}, 0.001, true};
  const auto pendulum = parseRobotModel(kPendulumUrdf, "pendulum.urdf");
  BulletWorld alone(*pendulum, memberSettings(scene_settings));
  BulletScene scene(scene_settings);
  BulletWorld swinging(*pendulum, memberSettings(scene_settings), scene);
  auto crate = std::make_unique<BulletWorld>(*parseRobotModel(boxUrdf("crate", 0.2, 1.0), "crate.urdf"),
                                             placedAt(scene_settings, {3, 0, 0.1}), scene);
  alone.setJointState(0, 1.0, 0.0);
  swinging.setJointState(0, 1.0, 0.0);
  ASSERT_EQ(scene.numMembers(), 2u);
  for (int k = 0; k < 3000; ++k) {
    if (k == 1000) crate = nullptr;  // the box leaves the scene
    alone.step();
    scene.step();
    ASSERT_EQ(swinging.jointPosition(0), alone.jointPosition(0)) << "step " << k;
  }
  EXPECT_EQ(scene.numMembers(), 1u);
}

TEST(BulletScene, AMemberStartingInsideAnotherSaysHowDeepAndInWhat) {
  const SceneSettings scene_settings{{0, 0, -kG}, 0.001, true};
  BulletScene scene(scene_settings);
  BulletWorld table(*parseRobotModel(kTableUrdf, "table.urdf"), memberSettings(scene_settings), scene);
  // The 0.2 m box's centre 0.05 m above the table top: 0.05 m of it inside.
  BulletWorld sunk(*parseRobotModel(boxUrdf("crate", 0.2, 1.0), "crate.urdf"),
                   placedAt(scene_settings, {0.0, 0.0, 0.55}), scene);
  const MemberOverlap overlap = sunk.deepestMemberOverlap();
  EXPECT_EQ(overlap.link, "box");
  EXPECT_EQ(overlap.other, "robot 'table' link 'top'");
  EXPECT_NEAR(overlap.depth_m, 0.05, 2e-3);
  // Resting on the top, or beside it on the ground: nothing (the ground
  // plane is deepestGroundPenetration's).
  BulletWorld resting(*parseRobotModel(boxUrdf("crate", 0.2, 1.0), "crate.urdf"),
                      placedAt(scene_settings, {0.3, 0.3, 0.6}), scene);
  EXPECT_LT(resting.deepestMemberOverlap().depth_m, 1e-3);
  BulletWorld aside(*parseRobotModel(boxUrdf("crate", 0.2, 1.0), "crate.urdf"),
                    placedAt(scene_settings, {2.0, 0.0, 0.05}), scene);
  EXPECT_EQ(aside.deepestMemberOverlap().other, "");
  EXPECT_NEAR(aside.deepestGroundPenetration().depth_m, 0.05, 2e-3);
}

TEST(BulletScene, MemberSettingsMustMatchTheScene) {
  const SceneSettings scene_settings{{0, 0, -kG}, 0.001, true};
  BulletScene scene(scene_settings);
  const auto model = parseRobotModel(boxUrdf("crate", 0.2, 1.0), "crate.urdf");
  WorldSettings other_step = memberSettings(scene_settings);
  other_step.time_step_s = 0.002;
  try {
    BulletWorld box(*model, other_step, scene);
    FAIL() << "a member with another time step was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("time step of 0.002"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("crate"), std::string::npos) << e.what();
  }
  WorldSettings no_ground = memberSettings(scene_settings);
  no_ground.ground_plane = false;
  EXPECT_THROW(BulletWorld(*model, no_ground, scene), ConfigError);
  WorldSettings moon = memberSettings(scene_settings);
  moon.gravity = Eigen::Vector3d(0, 0, -1.62);
  EXPECT_THROW(BulletWorld(*model, moon, scene), ConfigError);
  EXPECT_EQ(scene.numMembers(), 0u) << "a refused member leaves nothing behind";
  EXPECT_THROW(BulletScene(SceneSettings{{0, 0, -kG}, 0.0, false}), ConfigError);
}

}  // namespace
}  // namespace servoloop::sim_bullet
