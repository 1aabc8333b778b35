#include "servoloop/hardware_interface/simulated_robot_hw.hpp"

#include "servoloop/core/errors.hpp"

namespace servoloop::hardware_interface {

void SimulatedRobotHW::joinWorld(SimulatedWorld& world) {
  if (world.robotsTouch()) {
    throw ConfigError(
        "this simulator simulates each robot on its own and cannot build it into a world whose robots touch "
        "each other; use the world's own backend for every simulated robot");
  }
}

}  // namespace servoloop::hardware_interface
