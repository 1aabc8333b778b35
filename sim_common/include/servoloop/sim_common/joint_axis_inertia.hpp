#pragma once
// The inertia a joint's actuator feels when every other joint is held still:
// the mass properties of the joint's child link and everything beyond it (its
// subtree, all joints at position 0), about the joint axis.
#include <string>

#include <urdf_model/model.h>

namespace servoloop::sim_common {

// Non-real-time. Revolute and continuous joints: Σ over the subtree's links of
// aᵀ·I_com·a + m·d², with a the joint axis and d the distance of the link's
// centre of mass from the axis line (parallel-axis theorem), in kg·m².
// Prismatic joints: the subtree's total mass, in kg. Links without <inertial>
// count as massless. Throws servoloop::ConfigError naming the joint when it
// is unknown, not movable, or its subtree has no inertia about the axis.
double jointAxisInertia(const urdf::ModelInterface& model, const std::string& joint_name);

}  // namespace servoloop::sim_common
