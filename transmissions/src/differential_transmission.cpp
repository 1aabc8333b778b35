#include "servoloop/transmissions/differential_transmission.hpp"

namespace servoloop::transmissions {

DifferentialTransmission::DifferentialTransmission(const TwoValues& actuator_reductions,
                                                   const TwoValues& joint_reductions, const TwoValues& joint_offsets)
    : TwoByTwoTransmission("DifferentialTransmission", actuator_reductions, joint_reductions, joint_offsets) {}

TwoValues DifferentialTransmission::toJointEffort(const TwoValues& actuator_effort, const TwoValues& a,
                                                  const TwoValues& j) noexcept {
  const double t1 = a[0] * actuator_effort[0];
  const double t2 = a[1] * actuator_effort[1];
  return {j[0] * (t1 + t2), j[1] * (t1 - t2)};
}

TwoValues DifferentialTransmission::toActuatorEffort(const TwoValues& joint_effort, const TwoValues& a,
                                                     const TwoValues& j) noexcept {
  const double t1 = joint_effort[0] / j[0];
  const double t2 = joint_effort[1] / j[1];
  return {(t1 + t2) / (2.0 * a[0]), (t1 - t2) / (2.0 * a[1])};
}

TwoValues DifferentialTransmission::toJointMotion(const TwoValues& actuator_motion, const TwoValues& a,
                                                  const TwoValues& j) noexcept {
  const double sum = actuator_motion[0] / a[0] + actuator_motion[1] / a[1];
  const double difference = actuator_motion[0] / a[0] - actuator_motion[1] / a[1];
  return {sum / (2.0 * j[0]), difference / (2.0 * j[1])};
}

TwoValues DifferentialTransmission::toActuatorMotion(const TwoValues& joint_motion, const TwoValues& a,
                                                     const TwoValues& j) noexcept {
  return {(j[0] * joint_motion[0] + j[1] * joint_motion[1]) * a[0],
          (j[0] * joint_motion[0] - j[1] * joint_motion[1]) * a[1]};
}

}  // namespace servoloop::transmissions
