// Registers the backend with servoloop's plugin system: kind robot_hw (the
// base class's kPluginKind), type "first_order" — the name a launch file's
// world.backend or `servoloop launch --backend first_order` selects.
#include "my_backends/first_order_robot_hw.hpp"
#include "servoloop/plugin/plugin_register.hpp"

SERVOLOOP_REGISTER_PLUGIN(my_backends::FirstOrderRobotHW, servoloop::hardware_interface::RobotHW,
                          "first_order")
