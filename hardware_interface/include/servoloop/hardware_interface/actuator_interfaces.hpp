#pragma once
// Actuator-space interfaces: what the hardware (or a simulated motor) offers
// before transmissions map it to joints.
#include "servoloop/hardware_interface/actuator_handle.hpp"
#include "servoloop/hardware_interface/actuator_state_handle.hpp"
#include "servoloop/hardware_interface/resource_manager.hpp"

namespace servoloop::hardware_interface {

class ActuatorStateInterface : public ResourceManager<ActuatorStateHandle, false> {
 public:
  const char* name() const override { return "ActuatorStateInterface"; }
};

class ActuatorCommandInterface : public ResourceManager<ActuatorHandle, true> {};

class EffortActuatorInterface : public ActuatorCommandInterface {
 public:
  const char* name() const override { return "EffortActuatorInterface"; }
};

class VelocityActuatorInterface : public ActuatorCommandInterface {
 public:
  const char* name() const override { return "VelocityActuatorInterface"; }
};

class PositionActuatorInterface : public ActuatorCommandInterface {
 public:
  const char* name() const override { return "PositionActuatorInterface"; }
};

}  // namespace servoloop::hardware_interface
