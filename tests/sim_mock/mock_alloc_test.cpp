// 100,000 read/write/step cycles of the mock backend allocate nothing,
// through every command mode, a controller switch and the emergency stop.
#include <cmath>

#include <gtest/gtest.h>

#include "alloc_counter.hpp"
#include "backend_test_workloads.hpp"
#include "mock_robot_hw.hpp"

namespace servoloop::sim_mock {
namespace {

TEST(MockRobotHWAllocation, HundredThousandCyclesAllocateNothing) {
  MockRobotHW hw;
  hw.init(sim_testing::makeInfo(
      sim_testing::armUrdf(50.0, sim_testing::kAllJointInterfaces, "revolute", sim_testing::kArmLimitsWithSoftLimits),
      "actuators: {arm_motor: {max_effort: 0.2, rotor_inertia: 1.0e-4}}"));
  sim_testing::AllModesArmWorkload workload(hw, 0.001, 0.0001);

  servoloop::testing::AllocationCounter counter;
  const double checksum = workload.run(100000);
  EXPECT_EQ(counter.allocations(), 0u);
  EXPECT_TRUE(std::isfinite(checksum));
}

}  // namespace
}  // namespace servoloop::sim_mock
