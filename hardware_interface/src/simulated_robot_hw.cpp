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

void SimulatedRobotHW::setJointPositions(const std::vector<std::string>& /*joints*/,
                                         const std::vector<double>& /*positions*/) {
  throw Error("this simulator cannot move its joints directly (set_model_configuration)");
}

void SimulatedRobotHW::setBaseState(const BaseGroundTruth& /*state*/) {
  throw Error("this simulator has no floating base to move (set_model_state)");
}

}  // namespace servoloop::hardware_interface
