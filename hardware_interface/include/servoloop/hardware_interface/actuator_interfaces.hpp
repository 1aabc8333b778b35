#pragma once
// Actuator-space interfaces: what the hardware (or a simulated motor) offers
// before transmissions map it to joints.
#include "servoloop/hardware_interface/actuator_handle.hpp"
#include "servoloop/hardware_interface/actuator_state_handle.hpp"
#include "servoloop/hardware_interface/resource_manager.hpp"

namespace servoloop::hardware_interface {

// Instantiated once, in the hardware_interface library (interfaces.cpp), with
// each interface's name(): controllers that use these interfaces compile none
// of their code.
extern template class ResourceManager<ActuatorStateHandle, false>;
extern template class ResourceManager<ActuatorHandle, true>;

class ActuatorStateInterface : public ResourceManager<ActuatorStateHandle, false> {
 public:
  const char* name() const override;
};

class ActuatorCommandInterface : public ResourceManager<ActuatorHandle, true> {};

class EffortActuatorInterface : public ActuatorCommandInterface {
 public:
  const char* name() const override;
};

class VelocityActuatorInterface : public ActuatorCommandInterface {
 public:
  const char* name() const override;
};

class PositionActuatorInterface : public ActuatorCommandInterface {
 public:
  const char* name() const override;
};

}  // namespace servoloop::hardware_interface
