#pragma once
#include "servoloop/sim_common/sim_robot_hw.hpp"

namespace servoloop::sim_bullet {

// The "bullet" backend: SimRobotHW (transmissions, limits, command modes,
// emergency stop) on a Bullet Featherstone world (BulletPhysics).
class BulletRobotHW final : public sim_common::SimRobotHW {
 public:
  BulletRobotHW();
};

}  // namespace servoloop::sim_bullet
