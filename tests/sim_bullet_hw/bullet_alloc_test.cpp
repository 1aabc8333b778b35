// 100,000 read/write/step cycles of the bullet backend allocate nothing:
// counted through global operator new and Bullet's own allocator hook.
#include <cmath>

#include <gtest/gtest.h>

#include "alloc_counter.hpp"
#include "bullet_alloc_hook.hpp"
#include "backend_test_workloads.hpp"
#include "bullet_robot_hw.hpp"

namespace servoloop::sim_bullet {
namespace {

namespace bullet_alloc = servoloop::testing::bullet_alloc;

TEST(BulletRobotHWAllocation, HundredThousandCyclesAllocateNothing) {
  BulletRobotHW hw;
  hw.init(sim_testing::makeInfo(
      sim_testing::armUrdf(50.0, sim_testing::kAllJointInterfaces, "revolute", sim_testing::kArmLimitsWithSoftLimits),
      "{sim: {ground_plane: true}, actuators: {arm_motor: {max_effort: 0.2, rotor_inertia: 1.0e-4}}}"));
  sim_testing::AllModesArmWorkload workload(hw, 0.01, 0.01);
  // Warm-up: Bullet sizes its solver pools on the first steps of each mode.
  workload.run(30000);
  hw.setEmergencyStop(false);

  ASSERT_TRUE(bullet_alloc::kInstalled);
  ASSERT_GT(bullet_alloc::all.load(), 0u) << "the hook must see Bullet's allocations";
  const std::size_t bullet_allocations_before = bullet_alloc::all.load();
  servoloop::testing::AllocationCounter counter;
  const double checksum = workload.run(100000);
  EXPECT_EQ(counter.allocations(), 0u);
  EXPECT_EQ(bullet_alloc::all.load() - bullet_allocations_before, 0u);
  EXPECT_TRUE(std::isfinite(checksum));
}

}  // namespace
}  // namespace servoloop::sim_bullet
