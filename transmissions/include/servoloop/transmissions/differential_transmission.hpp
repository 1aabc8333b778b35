#pragma once
#include <array>

#include "servoloop/transmissions/transmission.hpp"

namespace servoloop::transmissions {

// Two actuators driving two joints through a differential (e.g. a wrist's
// pitch/roll): the sum of the actuator motions moves joint 1, their difference
// joint 2. With actuator reductions a, joint reductions j and joint offsets o:
//   τj1 = j1(a1τa1 + a2τa2),            τj2 = j2(a1τa1 − a2τa2)
//   ẋj1 = (ẋa1/a1 + ẋa2/a2)/(2j1),      ẋj2 = (ẋa1/a1 − ẋa2/a2)/(2j2)
//   xj  = as ẋj, plus o.
class DifferentialTransmission final : public Transmission {
 public:
  // Throws servoloop::ConfigError naming the first zero or non-finite
  // reduction (or non-finite offset).
  DifferentialTransmission(const std::array<double, 2>& actuator_reductions,
                           const std::array<double, 2>& joint_reductions,
                           const std::array<double, 2>& joint_offsets = {0.0, 0.0});

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

  std::size_t numActuators() const noexcept override { return 2; }
  std::size_t numJoints() const noexcept override { return 2; }

  const std::array<double, 2>& actuatorReductions() const noexcept { return actuator_reductions_; }
  const std::array<double, 2>& jointReductions() const noexcept { return joint_reductions_; }
  const std::array<double, 2>& jointOffsets() const noexcept { return joint_offsets_; }

 private:
  std::array<double, 2> actuator_reductions_;
  std::array<double, 2> joint_reductions_;
  std::array<double, 2> joint_offsets_;  // rad or m, in joint space
};

}  // namespace servoloop::transmissions
