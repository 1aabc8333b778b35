#pragma once
#include "servoloop/hardware_interface/actuator_state_handle.hpp"

namespace servoloop::hardware_interface {

// An actuator's state plus one command, in actuator space.
class ActuatorHandle : public ActuatorStateHandle {
 public:
  ActuatorHandle() = default;
  // Throws servoloop::Error if command is null.
  ActuatorHandle(const ActuatorStateHandle& state, double* command);

  void setCommand(double command) { *command_ = command; }
  double getCommand() const { return *command_; }
  double* getCommandPtr() const { return command_; }

 private:
  double* command_ = nullptr;
};

}  // namespace servoloop::hardware_interface
