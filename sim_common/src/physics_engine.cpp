// PhysicsEngine's batch access, through the per-joint methods.
#include "servoloop/sim_common/physics_engine.hpp"

namespace servoloop::sim_common {

void PhysicsEngine::readJointStates(std::span<EngineJointState> states) const noexcept {
  readJointStatesVia(*this, states);
}

void PhysicsEngine::applyJointCommands(std::span<const AppliedJointCommand> commands) noexcept {
  applyJointCommandsVia(*this, commands);
}

}  // namespace servoloop::sim_common
