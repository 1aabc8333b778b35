#pragma once
#include <array>

#include "servoloop/transmissions/transmission.hpp"

namespace servoloop::transmissions {

// Two actuators driving two joints where actuator 1 moves joint 1 alone and
// joint 2 is driven by actuator 2 relative to joint 1 (a four-bar linkage
// carrying the second joint's drive across the first). With actuator
// reductions a, joint reductions j and joint offsets o:
//   τj1 = j1·a1·τa1,          τj2 = j2(a2τa2 − j1a1τa1)
//   ẋj1 = ẋa1/(j1a1),         ẋj2 = (ẋa2/a2 − ẋa1/(j1a1))/j2
//   xj  = as ẋj, plus o.
class FourBarLinkageTransmission final : public Transmission {
 public:
  // Throws servoloop::ConfigError naming the first zero or non-finite
  // reduction (or non-finite offset).
  FourBarLinkageTransmission(const std::array<double, 2>& actuator_reductions,
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
