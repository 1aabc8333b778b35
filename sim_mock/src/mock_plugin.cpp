// Registers the mock backend with the plugin system: type "mock", kind robot_hw.
#include "mock_robot_hw.hpp"
#include "servoloop/plugin/plugin_register.hpp"

SERVOLOOP_REGISTER_PLUGIN(servoloop::sim_mock::MockRobotHW, servoloop::hardware_interface::RobotHW,
                          "mock")
