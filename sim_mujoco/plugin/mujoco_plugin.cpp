// Registers the MuJoCo backend with the plugin system: type "mujoco" (kind
// robot_hw), and the world its robots share, type "mujoco/world" (kind sim_world).
#include "mujoco_robot_hw.hpp"
#include "servoloop/plugin/plugin_register.hpp"
#include "servoloop/sim_mujoco/mujoco_world.hpp"

SERVOLOOP_REGISTER_PLUGIN(servoloop::sim_mujoco::MujocoRobotHW, servoloop::hardware_interface::RobotHW,
                          "mujoco")
SERVOLOOP_REGISTER_PLUGIN(servoloop::sim_mujoco::MujocoWorld, servoloop::hardware_interface::SimulatedWorld,
                          "mujoco/world")
