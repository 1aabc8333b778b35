#include "mock_robot_hw.hpp"

#include <memory>

#include "mock_physics.hpp"

namespace servoloop::sim_mock {

MockRobotHW::MockRobotHW() : SimRobotHW(std::make_unique<MockPhysics>()) {}

}  // namespace servoloop::sim_mock
