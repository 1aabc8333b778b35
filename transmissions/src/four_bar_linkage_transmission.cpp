#include "servoloop/transmissions/four_bar_linkage_transmission.hpp"

#include <cassert>

#include "reduction_check.hpp"

namespace servoloop::transmissions {

FourBarLinkageTransmission::FourBarLinkageTransmission(
    const std::array<double, 2>& actuator_reductions, const std::array<double, 2>& joint_reductions,
    const std::array<double, 2>& joint_offsets)
    : actuator_reductions_(actuator_reductions),
      joint_reductions_(joint_reductions),
      joint_offsets_(joint_offsets) {
  constexpr const char* kName = "FourBarLinkageTransmission";
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

Pair fourBarToJoint(double a1_value, double a2_value, const std::array<double, 2>& a,
                    const std::array<double, 2>& j) noexcept {
  const double joint1 = a1_value / (j[0] * a[0]);
  return {joint1, (a2_value / a[1] - joint1) / j[1]};
}

Pair fourBarToActuator(double j1_value, double j2_value, const std::array<double, 2>& a,
                       const std::array<double, 2>& j) noexcept {
  return {j[0] * a[0] * j1_value, (j1_value + j[1] * j2_value) * a[1]};
}
}  // namespace

void FourBarLinkageTransmission::actuatorToJointEffort(const ActuatorData& actuator,
                                                       JointData& joint) const noexcept {
  assert(actuator.effort.size() == 2 && joint.effort.size() == 2);
  const auto& a = actuator_reductions_;
  const auto& j = joint_reductions_;
  const double joint1 = j[0] * a[0] * *actuator.effort[0];
  *joint.effort[0] = joint1;
  *joint.effort[1] = j[1] * (a[1] * *actuator.effort[1] - joint1);
}

void FourBarLinkageTransmission::actuatorToJointVelocity(const ActuatorData& actuator,
                                                         JointData& joint) const noexcept {
  assert(actuator.velocity.size() == 2 && joint.velocity.size() == 2);
  const Pair v = fourBarToJoint(*actuator.velocity[0], *actuator.velocity[1], actuator_reductions_,
                                joint_reductions_);
  *joint.velocity[0] = v.first;
  *joint.velocity[1] = v.second;
}

void FourBarLinkageTransmission::actuatorToJointPosition(const ActuatorData& actuator,
                                                         JointData& joint) const noexcept {
  assert(actuator.position.size() == 2 && joint.position.size() == 2);
  const Pair x = fourBarToJoint(*actuator.position[0], *actuator.position[1], actuator_reductions_,
                                joint_reductions_);
  *joint.position[0] = x.first + joint_offsets_[0];
  *joint.position[1] = x.second + joint_offsets_[1];
}

void FourBarLinkageTransmission::jointToActuatorEffort(const JointData& joint,
                                                       ActuatorData& actuator) const noexcept {
  assert(actuator.effort.size() == 2 && joint.effort.size() == 2);
  const auto& a = actuator_reductions_;
  const auto& j = joint_reductions_;
  *actuator.effort[0] = *joint.effort[0] / (a[0] * j[0]);
  *actuator.effort[1] = (*joint.effort[0] + *joint.effort[1] / j[1]) / a[1];
}

void FourBarLinkageTransmission::jointToActuatorVelocity(const JointData& joint,
                                                         ActuatorData& actuator) const noexcept {
  assert(actuator.velocity.size() == 2 && joint.velocity.size() == 2);
  const Pair v = fourBarToActuator(*joint.velocity[0], *joint.velocity[1], actuator_reductions_,
                                   joint_reductions_);
  *actuator.velocity[0] = v.first;
  *actuator.velocity[1] = v.second;
}

void FourBarLinkageTransmission::jointToActuatorPosition(const JointData& joint,
                                                         ActuatorData& actuator) const noexcept {
  assert(actuator.position.size() == 2 && joint.position.size() == 2);
  const Pair x = fourBarToActuator(*joint.position[0] - joint_offsets_[0],
                                   *joint.position[1] - joint_offsets_[1], actuator_reductions_,
                                   joint_reductions_);
  *actuator.position[0] = x.first;
  *actuator.position[1] = x.second;
}

}  // namespace servoloop::transmissions
