#include "servoloop/transmissions/two_by_two_transmission.hpp"

#include "reduction_check.hpp"

namespace servoloop::transmissions::detail {

void requireUsableTwoByTwoParameters(const char* transmission, const TwoValues& actuator_reductions,
                                     const TwoValues& joint_reductions, const TwoValues& joint_offsets) {
  requireUsableReduction(transmission, "actuator_reductions[0]", actuator_reductions[0]);
  requireUsableReduction(transmission, "actuator_reductions[1]", actuator_reductions[1]);
  requireUsableReduction(transmission, "joint_reductions[0]", joint_reductions[0]);
  requireUsableReduction(transmission, "joint_reductions[1]", joint_reductions[1]);
  requireFiniteOffset(transmission, "joint_offsets[0]", joint_offsets[0]);
  requireFiniteOffset(transmission, "joint_offsets[1]", joint_offsets[1]);
}

}  // namespace servoloop::transmissions::detail
