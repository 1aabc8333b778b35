#include "servoloop/transmissions/differential_transmission.hpp"

#include <cassert>

#include "reduction_check.hpp"

namespace servoloop::transmissions {

DifferentialTransmission::DifferentialTransmission(const std::array<double, 2>& actuator_reductions,
                                                   const std::array<double, 2>& joint_reductions,
                                                   const std::array<double, 2>& joint_offsets)
    : actuator_reductions_(actuator_reductions),
      joint_reductions_(joint_reductions),
      joint_offsets_(joint_offsets) {
  constexpr const char* kName = "DifferentialTransmission";
  detail::requireUsableReduction(kName, "actuator_reductions[0]", actuator_reductions[0]);
  detail::requireUsableReduction(kName, "actuator_reductions[1]", actuator_reductions[1]);
  detail::requireUsableReduction(kName, "joint_reductions[0]", joint_reductions[0]);
  detail::requireUsableReduction(kName, "joint_reductions[1]", joint_reductions[1]);
  detail::requireFiniteOffset(kName, "joint_offsets[0]", joint_offsets[0]);
  detail::requireFiniteOffset(kName, "joint_offsets[1]", joint_offsets[1]);
}

// Velocity and position share one formula; only the offset differs.
namespace {
struct Pair {
  double first;
  double second;
};

Pair differentialToJoint(double a1_value, double a2_value, const std::array<double, 2>& a,
                         const std::array<double, 2>& j) noexcept {
  const double sum = a1_value / a[0] + a2_value / a[1];
  const double difference = a1_value / a[0] - a2_value / a[1];
  return {sum / (2.0 * j[0]), difference / (2.0 * j[1])};
}

Pair differentialToActuator(double j1_value, double j2_value, const std::array<double, 2>& a,
                            const std::array<double, 2>& j) noexcept {
  return {(j[0] * j1_value + j[1] * j2_value) * a[0], (j[0] * j1_value - j[1] * j2_value) * a[1]};
}
}  // namespace

void DifferentialTransmission::actuatorToJointEffort(const ActuatorData& actuator,
                                                     JointData& joint) const noexcept {
  assert(actuator.effort.size() == 2 && joint.effort.size() == 2);
  const auto& a = actuator_reductions_;
  const auto& j = joint_reductions_;
  const double t1 = a[0] * *actuator.effort[0];
  const double t2 = a[1] * *actuator.effort[1];
  *joint.effort[0] = j[0] * (t1 + t2);
  *joint.effort[1] = j[1] * (t1 - t2);
}

void DifferentialTransmission::actuatorToJointVelocity(const ActuatorData& actuator,
                                                       JointData& joint) const noexcept {
  assert(actuator.velocity.size() == 2 && joint.velocity.size() == 2);
  const Pair v = differentialToJoint(*actuator.velocity[0], *actuator.velocity[1],
                                     actuator_reductions_, joint_reductions_);
  *joint.velocity[0] = v.first;
  *joint.velocity[1] = v.second;
}

void DifferentialTransmission::actuatorToJointPosition(const ActuatorData& actuator,
                                                       JointData& joint) const noexcept {
  assert(actuator.position.size() == 2 && joint.position.size() == 2);
  const Pair x = differentialToJoint(*actuator.position[0], *actuator.position[1],
                                     actuator_reductions_, joint_reductions_);
  *joint.position[0] = x.first + joint_offsets_[0];
  *joint.position[1] = x.second + joint_offsets_[1];
}

void DifferentialTransmission::jointToActuatorEffort(const JointData& joint,
                                                     ActuatorData& actuator) const noexcept {
  assert(actuator.effort.size() == 2 && joint.effort.size() == 2);
  const auto& a = actuator_reductions_;
  const auto& j = joint_reductions_;
  const double t1 = *joint.effort[0] / j[0];
  const double t2 = *joint.effort[1] / j[1];
  *actuator.effort[0] = (t1 + t2) / (2.0 * a[0]);
  *actuator.effort[1] = (t1 - t2) / (2.0 * a[1]);
}

void DifferentialTransmission::jointToActuatorVelocity(const JointData& joint,
                                                       ActuatorData& actuator) const noexcept {
  assert(actuator.velocity.size() == 2 && joint.velocity.size() == 2);
  const Pair v = differentialToActuator(*joint.velocity[0], *joint.velocity[1],
                                        actuator_reductions_, joint_reductions_);
  *actuator.velocity[0] = v.first;
  *actuator.velocity[1] = v.second;
}

void DifferentialTransmission::jointToActuatorPosition(const JointData& joint,
                                                       ActuatorData& actuator) const noexcept {
  assert(actuator.position.size() == 2 && joint.position.size() == 2);
  const Pair x = differentialToActuator(*joint.position[0] - joint_offsets_[0],
                                        *joint.position[1] - joint_offsets_[1],
                                        actuator_reductions_, joint_reductions_);
  *actuator.position[0] = x.first;
  *actuator.position[1] = x.second;
}

}  // namespace servoloop::transmissions
