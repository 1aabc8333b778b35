#include "mujoco_robot_hw.hpp"

#include <memory>

#include "servoloop/sim_mujoco/mujoco_physics.hpp"

namespace servoloop::sim_mujoco {

MujocoRobotHW::MujocoRobotHW() : SimRobotHW(std::make_unique<MujocoPhysics>()) {}

}  // namespace servoloop::sim_mujoco
