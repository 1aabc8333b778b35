// Enforcing joint limits runs every control cycle, so it must not touch the heap.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "alloc_counter.hpp"
#include "servoloop/hardware_interface/joint_limits_interface.hpp"

namespace hi = servoloop::hardware_interface;

TEST(JointLimitsAllocation, EveryHandleKindEnforcesWithoutAllocating) {
  // Four joints, one per handle kind, sharing nothing.
  double pos[4] = {0.1, 0.2, 0.3, 0.4}, vel[4] = {0, 0, 0, 0}, eff[4] = {0, 0, 0, 0};
  double cmd[4] = {0, 0, 0, 0};
  hi::JointHandle joints[4];
  for (int i = 0; i < 4; ++i) {
    joints[i] = hi::JointHandle(hi::JointStateHandle("j" + std::to_string(i), &pos[i], &vel[i], &eff[i]),
                                &cmd[i]);
  }
  hi::JointLimits limits;
  limits.has_position_limits = true;
  limits.min_position = -1.0;
  limits.max_position = 1.0;
  limits.has_velocity_limits = true;
  limits.max_velocity = 2.0;
  limits.has_acceleration_limits = true;
  limits.max_acceleration = 5.0;
  limits.has_effort_limits = true;
  limits.max_effort = 10.0;
  hi::SoftJointLimits soft;
  soft.min_position = -0.9;
  soft.max_position = 0.9;
  soft.k_position = 10.0;
  soft.k_velocity = 5.0;

  hi::EffortJointSaturationInterface effort_sat;
  hi::EffortJointSoftLimitsInterface effort_soft;
  hi::PositionJointSaturationInterface position_sat;
  hi::VelocityJointSaturationInterface velocity_sat;
  effort_sat.registerHandle(hi::EffortJointSaturationHandle(joints[0], limits));
  effort_soft.registerHandle(hi::EffortJointSoftLimitsHandle(joints[1], limits, soft));
  position_sat.registerHandle(hi::PositionJointSaturationHandle(joints[2], limits));
  velocity_sat.registerHandle(hi::VelocityJointSaturationHandle(joints[3], limits));

  const servoloop::Duration period(0.001);
  double largest_effort_seen = 0.0;
  servoloop::testing::AllocationCounter counter;
  for (int cycle = 0; cycle < 100000; ++cycle) {
    const double command = 20.0 * ((cycle % 7) - 3);  // swings past every limit
    for (double& c : cmd) c = command;
    effort_sat.enforceLimits(period);
    effort_soft.enforceLimits(period);
    position_sat.enforceLimits(period);
    velocity_sat.enforceLimits(period);
    largest_effort_seen = std::max(largest_effort_seen, std::abs(cmd[0]));
  }
  EXPECT_EQ(counter.allocations(), 0u);
  // The loop really enforced: the effort command never left [-10, 10].
  EXPECT_DOUBLE_EQ(largest_effort_seen, 10.0);

  // The counter itself counts (otherwise zero above would prove nothing).
  servoloop::testing::AllocationCounter check;
  void* p = ::operator new(16);  // a direct call cannot be elided, unlike a new-expression
  ::operator delete(p);
  EXPECT_EQ(check.allocations(), 1u);
}
