#include "bullet_robot_hw.hpp"

#include <memory>

#include "bullet_physics.hpp"

namespace servoloop::sim_bullet {

BulletRobotHW::BulletRobotHW() : SimRobotHW(std::make_unique<BulletPhysics>()) {}

}  // namespace servoloop::sim_bullet
