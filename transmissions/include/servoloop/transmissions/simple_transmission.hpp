#pragma once
#include "servoloop/transmissions/transmission.hpp"

namespace servoloop::transmissions {

// One actuator driving one joint through a gear of ratio n (actuator turns per
// joint turn; negative reverses the direction), with the joint's zero shifted
// by offset o:
//   joint effort = n · actuator effort,  joint velocity = actuator velocity / n,
//   joint position = actuator position / n + o.
class SimpleTransmission final : public Transmission {
 public:
  // Throws servoloop::ConfigError if reduction is zero or not finite, or the
  // offset is not finite.
  explicit SimpleTransmission(double reduction, double joint_offset = 0.0);

  void actuatorToJointEffort(const ActuatorData& actuator,
                             JointData& joint) const noexcept override;
  void actuatorToJointVelocity(const ActuatorData& actuator,
                               JointData& joint) const noexcept override;
  void actuatorToJointPosition(const ActuatorData& actuator,
                               JointData& joint) const noexcept override;
  void jointToActuatorEffort(const JointData& joint,
                             ActuatorData& actuator) const noexcept override;
  void jointToActuatorVelocity(const JointData& joint,
                               ActuatorData& actuator) const noexcept override;
  void jointToActuatorPosition(const JointData& joint,
                               ActuatorData& actuator) const noexcept override;

  std::size_t numActuators() const noexcept override { return 1; }
  std::size_t numJoints() const noexcept override { return 1; }

  double reduction() const noexcept { return reduction_; }
  double jointOffset() const noexcept { return joint_offset_; }

  // The maps on plain numbers, for callers that keep n and o themselves
  // (RobotTransmissions' fast path); the members above use them too.
  static double jointEffort(double actuator_effort, double n) noexcept { return n * actuator_effort; }
  static double jointVelocity(double actuator_velocity, double n) noexcept { return actuator_velocity / n; }
  static double jointPosition(double actuator_position, double n, double o) noexcept {
    return actuator_position / n + o;
  }
  static double actuatorEffort(double joint_effort, double n) noexcept { return joint_effort / n; }
  static double actuatorVelocity(double joint_velocity, double n) noexcept { return n * joint_velocity; }
  static double actuatorPosition(double joint_position, double n, double o) noexcept {
    return n * (joint_position - o);
  }

 private:
  double reduction_;
  double joint_offset_;  // rad or m, in joint space
};

}  // namespace servoloop::transmissions
