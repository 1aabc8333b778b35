#pragma once
#include <string>
#include <vector>

#include "servoloop/hardware_interface/hardware_info.hpp"
#include "servoloop/hardware_interface/robot_hw.hpp"
#include "servoloop/hardware_interface/simulated_world.hpp"

namespace servoloop::hardware_interface {

// A RobotHW whose hardware is a simulation: besides read/write, the control
// loop steps it in lockstep with simulated time. Every simulation backend
// (bullet, mujoco, mock) implements this one interface, so the same robot,
// controllers and YAML run on any of them.
// Ground truth of a floating robot's root link, world frame: the pose of the
// link frame, the velocity of its origin and its angular velocity (world axes).
struct BaseGroundTruth {
  double position[3] = {0.0, 0.0, 0.0};          // m
  double orientation[4] = {0.0, 0.0, 0.0, 1.0};  // quaternion x, y, z, w: link -> world
  double linear_velocity[3] = {0.0, 0.0, 0.0};   // m/s
  double angular_velocity[3] = {0.0, 0.0, 0.0};  // rad/s
};

class SimulatedRobotHW : public RobotHW {
 public:
  // Non-real-time, before init(): the robot is to live in `world`, which
  // must outlive it (simulated_world.hpp). A world whose robots are
  // simulated apart needs nothing (the default); a simulator that builds
  // into a shared world overrides this. Throws servoloop::ConfigError when
  // the robot cannot live in that world (another engine's).
  virtual void joinWorld(SimulatedWorld& world);

  // Non-real-time. The physics time step fixed at init (world settings).
  virtual Duration timeStep() const = 0;

  // Real-time. Advances the simulation by one timeStep(), applying the
  // actuator commands of the last write(); in a shared world, hands the
  // commands over and the world's step() advances the physics.
  virtual ReturnType step() = 0;

  // Simulated time: timeStep() times the steps taken since init or reset.
  virtual Time simTime() const = 0;

  // Non-real-time. Back to the initial state: initial joint positions, zero
  // velocities, zero commands, simulated time 0.
  virtual void reset() = 0;

  // Non-real-time, with no cycle running (the world paused between two):
  // moves the named joints to `positions` (rad or m), at rest, as Gazebo's
  // set_model_configuration does; the others stay. Throws servoloop::Error
  // naming an unknown joint, a non-finite position, or lists of different
  // lengths (then nothing moved). By default: refused (a simulator that
  // cannot move its joints directly).
  virtual void setJointPositions(const std::vector<std::string>& joints, const std::vector<double>& positions);

  // Real-time safe. While engaged, position commands freeze at the position
  // measured when it was engaged and effort/velocity commands are zero, as
  // gazebo_ros_control's emergency stop does.
  virtual void setEmergencyStop(bool engaged) = 0;

  // Real-time. The root link's state after the last step when the robot's
  // base floats; false (out untouched) for a fixed base or a simulator that
  // does not track it.
  virtual bool readBaseGroundTruth(BaseGroundTruth& /*out*/) const noexcept { return false; }

  // Non-real-time, with no cycle running (the world paused between two):
  // teleports a floating root link to `state` (pose and twist, world frame
  // and axes, as readBaseGroundTruth gives them), as Gazebo's
  // set_model_state does; the joints keep their positions and velocities.
  // The orientation is normalised. Throws servoloop::Error for a value that
  // is not a finite number, a zero quaternion, or a fixed base (nothing
  // moved). By default: refused (a simulator without a floating base).
  virtual void setBaseState(const BaseGroundTruth& state);
};

}  // namespace servoloop::hardware_interface
