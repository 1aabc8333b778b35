#include "servoloop/transmissions/simple_transmission.hpp"

#include <cassert>

#include "reduction_check.hpp"

namespace servoloop::transmissions {

SimpleTransmission::SimpleTransmission(double reduction, double joint_offset)
    : reduction_(reduction), joint_offset_(joint_offset) {
  detail::requireUsableReduction("SimpleTransmission", "reduction", reduction);
  detail::requireFiniteOffset("SimpleTransmission", "joint_offset", joint_offset);
}

void SimpleTransmission::actuatorToJointEffort(const ActuatorData& actuator,
                                               JointData& joint) const noexcept {
  assert(actuator.effort.size() == 1 && joint.effort.size() == 1);
  *joint.effort[0] = jointEffort(*actuator.effort[0], reduction_);
}

void SimpleTransmission::actuatorToJointVelocity(const ActuatorData& actuator,
                                                 JointData& joint) const noexcept {
  assert(actuator.velocity.size() == 1 && joint.velocity.size() == 1);
  *joint.velocity[0] = jointVelocity(*actuator.velocity[0], reduction_);
}

void SimpleTransmission::actuatorToJointPosition(const ActuatorData& actuator,
                                                 JointData& joint) const noexcept {
  assert(actuator.position.size() == 1 && joint.position.size() == 1);
  *joint.position[0] = jointPosition(*actuator.position[0], reduction_, joint_offset_);
}

void SimpleTransmission::jointToActuatorEffort(const JointData& joint,
                                               ActuatorData& actuator) const noexcept {
  assert(actuator.effort.size() == 1 && joint.effort.size() == 1);
  *actuator.effort[0] = actuatorEffort(*joint.effort[0], reduction_);
}

void SimpleTransmission::jointToActuatorVelocity(const JointData& joint,
                                                 ActuatorData& actuator) const noexcept {
  assert(actuator.velocity.size() == 1 && joint.velocity.size() == 1);
  *actuator.velocity[0] = actuatorVelocity(*joint.velocity[0], reduction_);
}

void SimpleTransmission::jointToActuatorPosition(const JointData& joint,
                                                 ActuatorData& actuator) const noexcept {
  assert(actuator.position.size() == 1 && joint.position.size() == 1);
  *actuator.position[0] = actuatorPosition(*joint.position[0], reduction_, joint_offset_);
}

}  // namespace servoloop::transmissions
