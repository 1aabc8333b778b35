// PhysicsEngine's defaults: batch access through the per-joint methods,
// joining a world whose robots are simulated apart, and no sensors.
#include "servoloop/sim_common/physics_engine.hpp"

#include <string>

#include "servoloop/core/errors.hpp"

namespace servoloop::sim_common {

void PhysicsEngine::joinWorld(hardware_interface::SimulatedWorld& world) {
  if (world.robotsTouch()) {
    throw ConfigError(std::string("the ") + name() +
                      " engine simulates each robot on its own and cannot build it into a world whose robots "
                      "touch each other; use the world's own backend for every simulated robot");
  }
}

void PhysicsEngine::setBaseState(const EngineBaseState& /*state*/) {
  throw Error(std::string("the ") + name() + " engine has no floating base to move");
}

std::size_t PhysicsEngine::trackLink(const std::string& link) {
  throw ConfigError(std::string("the ") + name() + " engine does not simulate sensors (link '" + link +
                    "'); use the bullet or mujoco backend for a robot with sensors");
}

std::size_t PhysicsEngine::trackJointWrench(const std::string& joint) {
  throw ConfigError(std::string("the ") + name() + " engine does not simulate force-torque sensors (joint '" + joint +
                    "'); use the bullet or mujoco backend for a robot with sensors");
}

std::size_t PhysicsEngine::trackContacts(const std::string& link) {
  throw ConfigError(std::string("the ") + name() + " engine does not simulate contact sensors (link '" + link +
                    "'); use the bullet or mujoco backend for a robot with sensors");
}

void PhysicsEngine::readJointStates(std::span<EngineJointState> states) const noexcept {
  readJointStatesVia(*this, states);
}

void PhysicsEngine::applyJointCommands(std::span<const AppliedJointCommand> commands) noexcept {
  applyJointCommandsVia(*this, commands);
}

}  // namespace servoloop::sim_common
