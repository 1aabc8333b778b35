// 100,000 read/write/step cycles of the bullet backend allocate nothing:
// counted through global operator new and Bullet's own allocator hook.
#include <atomic>
#include <cmath>
#include <cstdlib>

#include <LinearMath/btAlignedAllocator.h>
#include <gtest/gtest.h>

#include "alloc_counter.hpp"
#include "bullet_robot_hw.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "sim_test_support.hpp"

namespace servoloop::sim_bullet {
namespace {

namespace hi = hardware_interface;

std::atomic<std::size_t> bullet_allocations{0};
void* countingBulletAlloc(std::size_t size) {
  bullet_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size);
}
void bulletFree(void* p) { std::free(p); }

// Installed before any Bullet object exists, so every block is freed by the
// allocator that made it.
const bool kBulletHookInstalled = [] {
  btAlignedAllocSetCustom(countingBulletAlloc, bulletFree);
  return true;
}();

TEST(BulletRobotHWAllocation, HundredThousandCyclesAllocateNothing) {
  BulletRobotHW hw;
  const std::string limits =
      R"(<limit lower="-1" upper="1" effort="10" velocity="1"/>
         <safety_controller soft_lower_limit="-0.5" soft_upper_limit="0.5" k_position="10" k_velocity="2"/>)";
  hw.init(sim_testing::makeInfo(sim_testing::armUrdf(50.0, sim_testing::kAllJointInterfaces, "revolute", limits),
                                "{sim: {ground_plane: true}, actuators: {arm_motor: {max_effort: 0.2, rotor_inertia: 1.0e-4}}}"));
  const std::vector<hi::ControllerInfo> effort = {
      sim_testing::controllerClaiming("e", "EffortJointInterface", {"arm_joint"})};
  const std::vector<hi::ControllerInfo> velocity = {
      sim_testing::controllerClaiming("v", "VelocityJointInterface", {"arm_joint"})};
  const std::vector<hi::ControllerInfo> position = {
      sim_testing::controllerClaiming("p", "PositionJointInterface", {"arm_joint"})};
  hi::JointHandle effort_handle = hw.get<hi::EffortJointInterface>()->getHandle("arm_joint");
  hi::JointHandle velocity_handle = hw.get<hi::VelocityJointInterface>()->getHandle("arm_joint");
  hi::JointHandle position_handle = hw.get<hi::PositionJointInterface>()->getHandle("arm_joint");
  const Duration period(0.001);
  const auto run = [&](int cycles) {
    double checksum = 0.0;
    for (int k = 0; k < cycles; ++k) {
      if (k % 30000 == 0) hw.doSwitch(effort, position);
      if (k % 30000 == 10000) hw.doSwitch(velocity, effort);
      if (k % 30000 == 20000) hw.doSwitch(position, velocity);
      if (k % 5000 == 0) hw.setEmergencyStop((k / 5000) % 2 == 1);
      hw.read(Time(), period);
      effort_handle.setCommand(k % 7 - 3.0);
      velocity_handle.setCommand(0.01 * (k % 11));
      position_handle.setCommand(0.01 * (k % 13));
      hw.write(Time(), period);
      hw.step();
      checksum += effort_handle.getPosition();
    }
    return checksum;
  };
  // Warm-up: Bullet sizes its solver pools on the first steps of each mode.
  run(30000);
  hw.setEmergencyStop(false);

  ASSERT_TRUE(kBulletHookInstalled);
  ASSERT_GT(bullet_allocations.load(), 0u) << "the hook must see Bullet's allocations";
  const std::size_t bullet_allocations_before = bullet_allocations.load();
  servoloop::testing::AllocationCounter counter;
  const double checksum = run(100000);
  EXPECT_EQ(counter.allocations(), 0u);
  EXPECT_EQ(bullet_allocations.load() - bullet_allocations_before, 0u);
  EXPECT_TRUE(std::isfinite(checksum));
}

}  // namespace
}  // namespace servoloop::sim_bullet
