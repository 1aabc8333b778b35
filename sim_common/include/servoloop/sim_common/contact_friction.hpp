#pragma once
// Contact friction of a robot's links, read the Gazebo way from the URDF:
//
//   <gazebo reference="left_wheel_link">
//     <mu1>1.0</mu1>   <!-- Coulomb friction coefficient, first direction -->
//     <mu2>1.0</mu2>   <!-- second direction -->
//   </gazebo>
//
// (or in the older form Gazebo also reads, <mu1 value="1.0"/>, as PR2's and
// pybullet's racecar descriptions have it).
//
// A link without <mu1>/<mu2> has Gazebo's default, 1. servoloop's contacts are
// isotropic (Gazebo's first direction is arbitrary unless <fdir1> is given),
// so a link whose mu1 and mu2 differ takes the smaller of the two, with a note.
// The coefficient of a contact with the ground plane is the link's; both
// backends apply it per collision, also for links merged into their parent
// through fixed joints (a caster on the base).
#include <map>
#include <string>

#include <urdf_model/model.h>

namespace servoloop::sim_common {

// Gazebo's (ODE's) friction coefficient of a surface that sets none.
inline constexpr double kDefaultContactFriction = 1.0;

// Link name → friction coefficient (>= 0) for every link whose <gazebo
// reference> sets <mu1> or <mu2>. Non-real-time. Throws ConfigError naming
// `source_name`, the reference and the element for a value that is not a
// finite number >= 0. A <mu1>/<mu2> under a reference that names no link of
// `model` is ignored with a warning. Text that is not XML gives no entries
// (the URDF parser reports it).
std::map<std::string, double> urdfLinkFriction(const std::string& urdf_xml, const urdf::ModelInterface& model,
                                               const std::string& source_name);

// The coefficient of `link`: its entry in `friction`, else the default.
double linkFriction(const std::map<std::string, double>& friction, const std::string& link);

}  // namespace servoloop::sim_common
