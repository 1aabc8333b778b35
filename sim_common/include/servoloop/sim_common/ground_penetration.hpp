#pragma once
// A robot spawned with a link in the floor (a legged robot at the origin, an
// arm whose wrist hangs below its base) is pushed out by the contacts at the
// first step, a free-standing one thrown up, in every physics engine and
// without a word from it. The backends measure how deep the robot starts
// below the ground plane and warn with these words; resting on the floor, or a
// few millimetres into it, is fine.
#include <string>

namespace servoloop::sim_common {

// Deeper than this below z = 0 at the start gets the warning.
inline constexpr double kGroundPenetrationWarningDepth_m = 0.01;

// "<source>: link 'foot' starts 0.230 m below the ground plane ...; spawn it
// higher: a root z of at least ... m ...". `base_z_m` is the spawn pose's z;
// `root_is_world`: the URDF's root link is `world`, which the spawn pose does
// not move (the fix is then in the URDF or the start positions).
std::string groundPenetrationWarning(const std::string& source_name, const std::string& link, double depth_m,
                                     double base_z_m, bool root_is_world);

}  // namespace servoloop::sim_common
