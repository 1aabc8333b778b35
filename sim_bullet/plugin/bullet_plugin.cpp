// Registers the Bullet backend with the plugin system: type "bullet" (kind
// robot_hw), and the world its robots share, type "bullet/world" (kind sim_world).
#include "bullet_robot_hw.hpp"
#include "bullet_simulated_world.hpp"
#include "servoloop/plugin/plugin_register.hpp"

SERVOLOOP_REGISTER_PLUGIN(servoloop::sim_bullet::BulletRobotHW, servoloop::hardware_interface::RobotHW,
                          "bullet")
SERVOLOOP_REGISTER_PLUGIN(servoloop::sim_bullet::BulletSimulatedWorld, servoloop::hardware_interface::SimulatedWorld,
                          "bullet/world")
