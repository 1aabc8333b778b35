#pragma once
#include "servoloop/transmissions/two_by_two_transmission.hpp"

namespace servoloop::transmissions {

// Two actuators driving two joints where actuator 1 moves joint 1 alone and
// joint 2 is driven by actuator 2 relative to joint 1 (a four-bar linkage
// carrying the second joint's drive across the first). With actuator
// reductions a, joint reductions j and joint offsets o:
//   τj1 = j1·a1·τa1,          τj2 = j2(a2τa2 − j1a1τa1)
//   ẋj1 = ẋa1/(j1a1),         ẋj2 = (ẋa2/a2 − ẋa1/(j1a1))/j2
//   xj  = as ẋj, plus o.
class FourBarLinkageTransmission final : public TwoByTwoTransmission<FourBarLinkageTransmission> {
 public:
  // Throws servoloop::ConfigError naming the first zero or non-finite
  // reduction (or non-finite offset).
  FourBarLinkageTransmission(const TwoValues& actuator_reductions, const TwoValues& joint_reductions,
                             const TwoValues& joint_offsets = {0.0, 0.0});

  // The formulas above on plain numbers (a, j: the reductions), for
  // TwoByTwoTransmission's maps. Motion: velocity, or position less o.
  static TwoValues toJointEffort(const TwoValues& actuator_effort, const TwoValues& a, const TwoValues& j) noexcept;
  static TwoValues toActuatorEffort(const TwoValues& joint_effort, const TwoValues& a, const TwoValues& j) noexcept;
  static TwoValues toJointMotion(const TwoValues& actuator_motion, const TwoValues& a, const TwoValues& j) noexcept;
  static TwoValues toActuatorMotion(const TwoValues& joint_motion, const TwoValues& a, const TwoValues& j) noexcept;
};

}  // namespace servoloop::transmissions
