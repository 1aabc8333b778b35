// 100,000 read/write/step cycles of the mujoco backend allocate nothing:
// counted through global operator new and MuJoCo's own allocator hook
// (mju_user_malloc), in every command mode, with the emergency stop toggling
// and ground contacts possible.
#include <atomic>
#include <cmath>
#include <cstdlib>

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include "alloc_counter.hpp"
#include "backend_test_workloads.hpp"
#include "mujoco_robot_hw.hpp"

namespace servoloop::sim_mujoco {
namespace {

std::atomic<std::size_t> mujoco_allocations{0};
void* countingMujocoAlloc(std::size_t size) {
  mujoco_allocations.fetch_add(1, std::memory_order_relaxed);
  // MuJoCo's own allocator aligns to 64 bytes; keep that.
  return std::aligned_alloc(64, (size + 63) / 64 * 64);
}
void mujocoFree(void* p) { std::free(p); }

// Installed before any MuJoCo object exists, so every block is freed by the
// allocator that made it.
const bool kMujocoHookInstalled = [] {
  mju_user_malloc = countingMujocoAlloc;
  mju_user_free = mujocoFree;
  return true;
}();

TEST(MujocoRobotHWAllocation, HundredThousandCyclesAllocateNothing) {
  MujocoRobotHW hw;
  hw.init(sim_testing::makeInfo(
      sim_testing::armUrdf(50.0, sim_testing::kAllJointInterfaces, "revolute", sim_testing::kArmLimitsWithSoftLimits),
      "{sim: {ground_plane: true}, actuators: {arm_motor: {max_effort: 0.2, rotor_inertia: 1.0e-4}}}"));
  sim_testing::AllModesArmWorkload workload(hw, 0.01, 0.01);
  workload.run(30000);  // every mode once
  hw.setEmergencyStop(false);

  ASSERT_TRUE(kMujocoHookInstalled);
  ASSERT_GT(mujoco_allocations.load(), 0u) << "the hook must see MuJoCo's allocations";
  const std::size_t mujoco_allocations_before = mujoco_allocations.load();
  servoloop::testing::AllocationCounter counter;
  const double checksum = workload.run(100000);
  EXPECT_EQ(counter.allocations(), 0u);
  EXPECT_EQ(mujoco_allocations.load() - mujoco_allocations_before, 0u);
  EXPECT_TRUE(std::isfinite(checksum));
}

}  // namespace
}  // namespace servoloop::sim_mujoco
