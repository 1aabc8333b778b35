#pragma once
// What the transmissions with two actuators and two joints (differential,
// four-bar linkage) share: their parameters, checked once at construction,
// their size, and the six maps around the mechanism's formulas (reading and
// writing the two values, the joint offsets). A mechanism adds only its four
// formulas on plain numbers.
#include <array>
#include <cassert>

#include "servoloop/transmissions/transmission.hpp"

namespace servoloop::transmissions {

// Two values of one kind, one per actuator or per joint, in role order
// (actuator1/actuator2, joint1/joint2).
using TwoValues = std::array<double, 2>;

namespace detail {
// Non-real-time. Throws servoloop::ConfigError naming `transmission` (the
// class, e.g. "DifferentialTransmission") and the first zero or non-finite
// reduction, or non-finite offset.
void requireUsableTwoByTwoParameters(const char* transmission, const TwoValues& actuator_reductions,
                                     const TwoValues& joint_reductions, const TwoValues& joint_offsets);
}  // namespace detail

// `Mechanism` (the subclass) provides, with a = actuator reductions and
// j = joint reductions:
//   static TwoValues toJointEffort(const TwoValues& actuator_effort, a, j) noexcept;
//   static TwoValues toActuatorEffort(const TwoValues& joint_effort, a, j) noexcept;
//   static TwoValues toJointMotion(const TwoValues& actuator_motion, a, j) noexcept;
//   static TwoValues toActuatorMotion(const TwoValues& joint_motion, a, j) noexcept;
// where motion is a velocity, or a position without the joint offsets (the
// position map is the velocity map plus the offsets). The calls bind
// statically: one virtual call per map, as for any Transmission.
template <class Mechanism>
class TwoByTwoTransmission : public Transmission {
 public:
  void actuatorToJointEffort(const ActuatorData& actuator, JointData& joint) const noexcept final {
    assert(actuator.effort.size() == 2 && joint.effort.size() == 2);
    write(Mechanism::toJointEffort(read(actuator.effort), actuator_reductions_, joint_reductions_), joint.effort);
  }
  void actuatorToJointVelocity(const ActuatorData& actuator, JointData& joint) const noexcept final {
    assert(actuator.velocity.size() == 2 && joint.velocity.size() == 2);
    write(Mechanism::toJointMotion(read(actuator.velocity), actuator_reductions_, joint_reductions_),
          joint.velocity);
  }
  void actuatorToJointPosition(const ActuatorData& actuator, JointData& joint) const noexcept final {
    assert(actuator.position.size() == 2 && joint.position.size() == 2);
    const TwoValues x = Mechanism::toJointMotion(read(actuator.position), actuator_reductions_, joint_reductions_);
    *joint.position[0] = x[0] + joint_offsets_[0];
    *joint.position[1] = x[1] + joint_offsets_[1];
  }
  void jointToActuatorEffort(const JointData& joint, ActuatorData& actuator) const noexcept final {
    assert(actuator.effort.size() == 2 && joint.effort.size() == 2);
    write(Mechanism::toActuatorEffort(read(joint.effort), actuator_reductions_, joint_reductions_),
          actuator.effort);
  }
  void jointToActuatorVelocity(const JointData& joint, ActuatorData& actuator) const noexcept final {
    assert(actuator.velocity.size() == 2 && joint.velocity.size() == 2);
    write(Mechanism::toActuatorMotion(read(joint.velocity), actuator_reductions_, joint_reductions_),
          actuator.velocity);
  }
  void jointToActuatorPosition(const JointData& joint, ActuatorData& actuator) const noexcept final {
    assert(actuator.position.size() == 2 && joint.position.size() == 2);
    const TwoValues motion{*joint.position[0] - joint_offsets_[0], *joint.position[1] - joint_offsets_[1]};
    write(Mechanism::toActuatorMotion(motion, actuator_reductions_, joint_reductions_), actuator.position);
  }

  std::size_t numActuators() const noexcept final { return 2; }
  std::size_t numJoints() const noexcept final { return 2; }

  const TwoValues& actuatorReductions() const noexcept { return actuator_reductions_; }
  const TwoValues& jointReductions() const noexcept { return joint_reductions_; }
  const TwoValues& jointOffsets() const noexcept { return joint_offsets_; }  // rad or m, joint space

 protected:
  // Throws as detail::requireUsableTwoByTwoParameters, naming `transmission_name`.
  TwoByTwoTransmission(const char* transmission_name, const TwoValues& actuator_reductions,
                       const TwoValues& joint_reductions, const TwoValues& joint_offsets)
      : actuator_reductions_(actuator_reductions), joint_reductions_(joint_reductions), joint_offsets_(joint_offsets) {
    detail::requireUsableTwoByTwoParameters(transmission_name, actuator_reductions, joint_reductions, joint_offsets);
  }

 private:
  static TwoValues read(const std::vector<double*>& values) noexcept { return {*values[0], *values[1]}; }
  static void write(const TwoValues& from, const std::vector<double*>& to) noexcept {
    *to[0] = from[0];
    *to[1] = from[1];
  }

  TwoValues actuator_reductions_;
  TwoValues joint_reductions_;
  TwoValues joint_offsets_;
};

}  // namespace servoloop::transmissions
