#pragma once
#include "servoloop/hardware_interface/hardware_info.hpp"
#include "servoloop/hardware_interface/robot_hw.hpp"

namespace servoloop::hardware_interface {

// A RobotHW whose hardware is a simulation: besides read/write, the control
// loop steps it in lockstep with simulated time. Every simulation backend
// (bullet, mujoco, mock) implements this one interface, so the same robot,
// controllers and YAML run on any of them.
class SimulatedRobotHW : public RobotHW {
 public:
  // Non-real-time. The physics time step fixed at init (world settings).
  virtual Duration timeStep() const = 0;

  // Real-time. Advances the simulation by one timeStep(), applying the
  // actuator commands of the last write().
  virtual ReturnType step() = 0;

  // Simulated time: timeStep() times the steps taken since init or reset.
  virtual Time simTime() const = 0;

  // Non-real-time. Back to the initial state: initial joint positions, zero
  // velocities, zero commands, simulated time 0.
  virtual void reset() = 0;

  // Real-time safe. While engaged, position commands freeze at the position
  // measured when it was engaged and effort/velocity commands are zero, as
  // gazebo_ros_control's emergency stop does.
  virtual void setEmergencyStop(bool engaged) = 0;
};

}  // namespace servoloop::hardware_interface
