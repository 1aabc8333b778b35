// After construction, stepping and the joint setters/getters allocate nothing:
// counted through global operator new (servoloop's code) and through Bullet's
// own allocator hook (btAlignedAlloc, which calls malloc directly).
#include <atomic>
#include <cstdlib>

#include <LinearMath/btAlignedAllocator.h>
#include <gtest/gtest.h>

#include "alloc_counter.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/sim_bullet/bullet_world.hpp"

namespace servoloop::sim_bullet {
namespace {

std::atomic<std::size_t> bullet_allocations{0};
void* countingBulletAlloc(std::size_t size) {
  bullet_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size);
}
void bulletFree(void* p) { std::free(p); }

// Installed before any Bullet object exists, so every block is freed by the
// same allocator that made it.
const bool kBulletHookInstalled = [] {
  btAlignedAllocSetCustom(countingBulletAlloc, bulletFree);
  return true;
}();

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

  ASSERT_TRUE(kBulletHookInstalled);
  ASSERT_GT(bullet_allocations.load(), 0u) << "the hook must see Bullet's allocations";
  const std::size_t bullet_allocations_before = bullet_allocations.load();
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
  EXPECT_EQ(bullet_allocations.load() - bullet_allocations_before, 0u);
  EXPECT_GT(sum, 0.0);
}

}  // namespace
}  // namespace servoloop::sim_bullet
