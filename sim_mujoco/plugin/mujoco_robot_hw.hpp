#pragma once
#include "servoloop/sim_common/sim_robot_hw.hpp"

namespace servoloop::sim_mujoco {

// The "mujoco" backend: SimRobotHW (transmissions, limits, command modes,
// emergency stop) on a MuJoCo world (MujocoPhysics).
class MujocoRobotHW final : public sim_common::SimRobotHW {
 public:
  MujocoRobotHW();
};

}  // namespace servoloop::sim_mujoco
