// After construction, stepping and the joint setters/getters allocate nothing:
// counted through global operator new (servoloop's code) and through Bullet's
// own allocator hook (btAlignedAlloc, which calls malloc directly).
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "alloc_counter.hpp"
#include "bullet_alloc_hook.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/sim_bullet/bullet_scene.hpp"
#include "servoloop/sim_bullet/bullet_world.hpp"

namespace servoloop::sim_bullet {
namespace {

namespace bullet_alloc = servoloop::testing::bullet_alloc;

TEST(BulletWorldAllocation, SteadyStateStepAllocatesNothing) {
  const auto model = loadRobotModelFile(std::string(SERVOLOOP_SEED_DIR) +
                                        "/minimal_robot_description_w_jnt_ctl.urdf");
  WorldSettings settings;
  settings.ground_plane = true;
  BulletWorld world(*model, settings);
  world.setJointState(0, 1.0, 0.0);
  // Warm-up: Bullet sizes its solver pools on the first steps of each mode.
  for (int k = 0; k < 20; ++k) {
    world.setJointPositionTarget(0, 1.5);
    world.step();
  }
  for (int k = 0; k < 20; ++k) {
    world.setJointEffort(0, 10.0);
    world.step();
  }

  ASSERT_TRUE(bullet_alloc::kInstalled);
  ASSERT_GT(bullet_alloc::all.load(), 0u) << "the hook must see Bullet's allocations";
  const std::size_t bullet_allocations_before = bullet_alloc::all.load();
  servoloop::testing::AllocationCounter counter;
  double sum = 0.0;
  for (int k = 0; k < 1000; ++k) {
    if (k % 3 == 0) world.setJointEffort(0, 5.0);
    if (k % 3 == 1) world.setJointVelocityTarget(0, 0.1);
    if (k % 3 == 2) world.setJointPositionTarget(0, 1.2);
    world.step();
    sum += world.jointPosition(0) + world.jointVelocity(0) + world.time();
  }
  world.setJointState(0, 0.5, 0.0);
  EXPECT_EQ(counter.allocations(), 0u);
  EXPECT_EQ(bullet_alloc::all.load() - bullet_allocations_before, 0u);
  EXPECT_GT(sum, 0.0);
}

// Several robots and objects in one scene, touching: the seed arm moving, and
// a slider pushing a row of four boxes along the ground. Bullet sizes its
// contact algorithms and solver arrays for the contacts it has met, so the
// boxes are in contact with each other and the paddle before counting starts.
TEST(BulletWorldAllocation, SharedSceneStepAllocatesNothing) {
  const SceneSettings scene_settings{{0, 0, -9.81}, 0.001, true};
  BulletScene scene(scene_settings);
  WorldSettings settings;
  settings.ground_plane = true;
  const auto seed = loadRobotModelFile(std::string(SERVOLOOP_SEED_DIR) + "/minimal_robot_description_w_jnt_ctl.urdf");
  BulletWorld arm(*seed, settings, scene);
  const auto slider = parseRobotModel(R"(<robot name="slider"><link name="world"/>
    <joint name="rail" type="prismatic"><parent link="world"/><child link="paddle"/>
      <origin xyz="-1 1.5 0.12"/><axis xyz="1 0 0"/><limit lower="-5" upper="5" effort="100" velocity="10"/></joint>
    <link name="paddle"><inertial><mass value="5"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
      <collision><geometry><box size="0.05 0.4 0.2"/></geometry></collision></link></robot>)", "slider.urdf");
  BulletWorld pusher(*slider, settings, scene);
  const auto box = parseRobotModel(R"(<robot name="box"><link name="box"><inertial><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
      <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link></robot>)", "box.urdf");
  std::vector<std::unique_ptr<BulletWorld>> boxes;
  for (int i = 0; i < 4; ++i) {
    WorldSettings placed = settings;
    placed.initial_base_position = Eigen::Vector3d(-0.8 + 0.25 * i, 1.5, 0.1);
    boxes.push_back(std::make_unique<BulletWorld>(*box, placed, scene));
  }
  // Warm-up: the paddle reaches the row and pushes the boxes together.
  for (int k = 0; k < 2000; ++k) {
    pusher.setJointVelocityTarget(0, 0.5);
    arm.setJointEffort(0, 1.0);
    scene.step();
  }
  const std::size_t bullet_allocations_before = bullet_alloc::all.load();
  servoloop::testing::AllocationCounter counter;
  double sum = 0.0;
  for (int k = 0; k < 1000; ++k) {
    pusher.setJointVelocityTarget(0, 0.5);
    arm.setJointPositionTarget(0, 0.5);
    scene.step();
    sum += boxes.front()->baseState().position.x() + arm.jointPosition(0);
  }
  EXPECT_EQ(counter.allocations(), 0u);
  EXPECT_EQ(bullet_alloc::all.load() - bullet_allocations_before, 0u);
  EXPECT_GT(boxes.front()->baseState().position.x(), -0.3) << "the boxes were pushed";
  EXPECT_NE(sum, 0.0);
}

}  // namespace
}  // namespace servoloop::sim_bullet
