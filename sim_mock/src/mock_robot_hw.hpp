#pragma once
#include "servoloop/sim_common/sim_robot_hw.hpp"

namespace servoloop::sim_mock {

// The "mock" backend: SimRobotHW (transmissions, limits, command modes,
// emergency stop) on ideal actuators (MockPhysics) instead of a physics engine.
class MockRobotHW final : public sim_common::SimRobotHW {
 public:
  MockRobotHW();
};

}  // namespace servoloop::sim_mock
