#pragma once
#include "servoloop/transmissions/two_by_two_transmission.hpp"

namespace servoloop::transmissions {

// Two actuators driving two joints through a differential (e.g. a wrist's
// pitch/roll): the sum of the actuator motions moves joint 1, their difference
// joint 2. With actuator reductions a, joint reductions j and joint offsets o:
//   τj1 = j1(a1τa1 + a2τa2),            τj2 = j2(a1τa1 − a2τa2)
//   ẋj1 = (ẋa1/a1 + ẋa2/a2)/(2j1),      ẋj2 = (ẋa1/a1 − ẋa2/a2)/(2j2)
//   xj  = as ẋj, plus o.
class DifferentialTransmission final : public TwoByTwoTransmission<DifferentialTransmission> {
 public:
  // Throws servoloop::ConfigError naming the first zero or non-finite
  // reduction (or non-finite offset).
  DifferentialTransmission(const TwoValues& actuator_reductions, const TwoValues& joint_reductions,
                           const TwoValues& joint_offsets = {0.0, 0.0});

  // The formulas above on plain numbers (a, j: the reductions), for
  // TwoByTwoTransmission's maps. Motion: velocity, or position less o.
  static TwoValues toJointEffort(const TwoValues& actuator_effort, const TwoValues& a, const TwoValues& j) noexcept;
  static TwoValues toActuatorEffort(const TwoValues& joint_effort, const TwoValues& a, const TwoValues& j) noexcept;
  static TwoValues toJointMotion(const TwoValues& actuator_motion, const TwoValues& a, const TwoValues& j) noexcept;
  static TwoValues toActuatorMotion(const TwoValues& joint_motion, const TwoValues& a, const TwoValues& j) noexcept;
};

}  // namespace servoloop::transmissions
