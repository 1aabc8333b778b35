#pragma once
// What kind of URDF joint a transmission may drive (shared by the parser and
// the robot's transmission set).
#include <urdf_model/joint.h>

namespace servoloop::transmissions::detail {

// A joint with one degree of freedom that moves: revolute, continuous or prismatic.
inline bool isSingleDofMovable(const urdf::Joint& joint) {
  return joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::CONTINUOUS ||
         joint.type == urdf::Joint::PRISMATIC;
}

}  // namespace servoloop::transmissions::detail
