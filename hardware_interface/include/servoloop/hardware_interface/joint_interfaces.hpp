#pragma once
// Joint-space interfaces, as in ros_control. The state interface hands out
// read-only handles and claims nothing; each command interface hands out
// handles whose command means effort, velocity or position, and claims the
// joint for the controller that asked.
#include "servoloop/hardware_interface/joint_handle.hpp"
#include "servoloop/hardware_interface/joint_state_handle.hpp"
#include "servoloop/hardware_interface/resource_manager.hpp"

namespace servoloop::hardware_interface {

// Instantiated once, in the hardware_interface library (interfaces.cpp), with
// each interface's name(): controllers that use these interfaces compile none
// of their code.
extern template class ResourceManager<JointStateHandle, false>;
extern template class ResourceManager<JointHandle, true>;

class JointStateInterface : public ResourceManager<JointStateHandle, false> {
 public:
  const char* name() const override;
};

class JointCommandInterface : public ResourceManager<JointHandle, true> {};

class EffortJointInterface : public JointCommandInterface {
 public:
  const char* name() const override;
};

class VelocityJointInterface : public JointCommandInterface {
 public:
  const char* name() const override;
};

class PositionJointInterface : public JointCommandInterface {
 public:
  const char* name() const override;
};

}  // namespace servoloop::hardware_interface
