// PhysicsEngine's batch access, through the per-joint methods.
#include "servoloop/sim_common/physics_engine.hpp"

namespace servoloop::sim_common {

void PhysicsEngine::readJointStates(std::span<EngineJointState> states) const noexcept {
  for (std::size_t j = 0; j < states.size(); ++j) {
    states[j] = EngineJointState{jointPosition(j), jointVelocity(j), jointEffort(j)};
  }
}

void PhysicsEngine::applyJointCommands(std::span<const AppliedJointCommand> commands) noexcept {
  for (std::size_t j = 0; j < commands.size(); ++j) {
    const AppliedJointCommand& command = commands[j];
    switch (command.mode) {
      case JointCommandMode::none:
      case JointCommandMode::effort:
        setJointEffort(j, command.value);
        break;
      case JointCommandMode::velocity:
        setJointVelocityTarget(j, command.value);
        break;
      case JointCommandMode::position:
        setJointPositionTarget(j, command.value);
        break;
    }
  }
}

}  // namespace servoloop::sim_common
