#include "servoloop/transmissions/four_bar_linkage_transmission.hpp"

namespace servoloop::transmissions {

FourBarLinkageTransmission::FourBarLinkageTransmission(const TwoValues& actuator_reductions,
                                                       const TwoValues& joint_reductions,
                                                       const TwoValues& joint_offsets)
    : TwoByTwoTransmission("FourBarLinkageTransmission", actuator_reductions, joint_reductions, joint_offsets) {}

TwoValues FourBarLinkageTransmission::toJointEffort(const TwoValues& actuator_effort, const TwoValues& a,
                                                    const TwoValues& j) noexcept {
  const double joint1 = j[0] * a[0] * actuator_effort[0];
  return {joint1, j[1] * (a[1] * actuator_effort[1] - joint1)};
}

TwoValues FourBarLinkageTransmission::toActuatorEffort(const TwoValues& joint_effort, const TwoValues& a,
                                                       const TwoValues& j) noexcept {
  return {joint_effort[0] / (a[0] * j[0]), (joint_effort[0] + joint_effort[1] / j[1]) / a[1]};
}

TwoValues FourBarLinkageTransmission::toJointMotion(const TwoValues& actuator_motion, const TwoValues& a,
                                                    const TwoValues& j) noexcept {
  const double joint1 = actuator_motion[0] / (j[0] * a[0]);
  return {joint1, (actuator_motion[1] / a[1] - joint1) / j[1]};
}

TwoValues FourBarLinkageTransmission::toActuatorMotion(const TwoValues& joint_motion, const TwoValues& a,
                                                       const TwoValues& j) noexcept {
  return {j[0] * a[0] * joint_motion[0], (joint_motion[0] + j[1] * joint_motion[1]) * a[1]};
}

}  // namespace servoloop::transmissions
