// Registers the Bullet backend with the plugin system: type "bullet", kind robot_hw.
#include "bullet_robot_hw.hpp"
#include "servoloop/plugin/plugin_register.hpp"

SERVOLOOP_REGISTER_PLUGIN(servoloop::sim_bullet::BulletRobotHW, servoloop::hardware_interface::RobotHW,
                          "bullet")
