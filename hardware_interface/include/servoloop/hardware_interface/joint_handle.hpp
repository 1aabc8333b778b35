#pragma once
#include "servoloop/hardware_interface/joint_state_handle.hpp"

namespace servoloop::hardware_interface {

// A joint's state plus one command (effort, velocity or position, depending on
// the interface that handed it out), in joint space.
class JointHandle : public JointStateHandle {
 public:
  JointHandle() = default;
  // Throws servoloop::Error if command is null.
  JointHandle(const JointStateHandle& state, double* command);

  void setCommand(double command) { *command_ = command; }
  double getCommand() const { return *command_; }
  double* getCommandPtr() const { return command_; }

 private:
  double* command_ = nullptr;
};

}  // namespace servoloop::hardware_interface
