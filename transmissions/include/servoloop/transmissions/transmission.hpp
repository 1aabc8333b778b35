#pragma once
// The transmission abstraction, as in ros_control: a mechanism that maps the
// values of a few actuators (motor side) to the values of a few joints (load
// side) and back, for effort, velocity and position separately.
#include <cstddef>
#include <vector>

namespace servoloop::transmissions {

// Pointers to actuator-space values (motor rad, rad/s, N·m; or m, m/s, N for
// linear motors), one entry per actuator of the transmission, in the
// transmission's actuator order. A map reads or writes only the field it names.
struct ActuatorData {
  std::vector<double*> position;
  std::vector<double*> velocity;
  std::vector<double*> effort;
};

// Pointers to joint-space values (rad or m, rad/s or m/s, N·m or N), one entry
// per joint of the transmission, in the transmission's joint order.
struct JointData {
  std::vector<double*> position;
  std::vector<double*> velocity;
  std::vector<double*> effort;
};

// Base of every transmission. The six maps run on the real-time thread: they
// only read and write through the given pointers, never allocate, never throw.
// Precondition (checked by assert in debug builds only): the vectors used by a
// map hold numActuators() / numJoints() non-null pointers.
class Transmission {
 public:
  virtual ~Transmission() = default;

  // Real-time. Joint efforts from actuator efforts.
  virtual void actuatorToJointEffort(const ActuatorData& actuator,
                                     JointData& joint) const noexcept = 0;
  // Real-time. Joint velocities from actuator velocities.
  virtual void actuatorToJointVelocity(const ActuatorData& actuator,
                                       JointData& joint) const noexcept = 0;
  // Real-time. Joint positions from actuator positions (joint offsets applied).
  virtual void actuatorToJointPosition(const ActuatorData& actuator,
                                       JointData& joint) const noexcept = 0;

  // Real-time. Actuator efforts from joint efforts (inverse of actuatorToJointEffort).
  virtual void jointToActuatorEffort(const JointData& joint,
                                     ActuatorData& actuator) const noexcept = 0;
  // Real-time. Actuator velocities from joint velocities.
  virtual void jointToActuatorVelocity(const JointData& joint,
                                       ActuatorData& actuator) const noexcept = 0;
  // Real-time. Actuator positions from joint positions (joint offsets removed).
  virtual void jointToActuatorPosition(const JointData& joint,
                                       ActuatorData& actuator) const noexcept = 0;

  virtual std::size_t numActuators() const noexcept = 0;
  virtual std::size_t numJoints() const noexcept = 0;
};

}  // namespace servoloop::transmissions
