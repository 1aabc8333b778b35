// Registers the MuJoCo backend with the plugin system: type "mujoco", kind robot_hw.
#include "mujoco_robot_hw.hpp"
#include "servoloop/plugin/plugin_register.hpp"

SERVOLOOP_REGISTER_PLUGIN(servoloop::sim_mujoco::MujocoRobotHW, servoloop::hardware_interface::RobotHW,
                          "mujoco")
