#pragma once
// A robot spawned with a link in the floor (a legged robot at the origin, an
// arm whose wrist hangs below its base) is pushed out by the contacts at the
// first step, a free-standing one thrown up, in every physics engine and
// without a word from it. Each backend measures how deep the robot starts
// below the ground plane; this warns about it in the same words for all of
// them. Resting on the floor, or a few millimetres into it, is fine.
#include <string>

#include <urdf_model/model.h>

#include "servoloop/sim_common/sim_settings.hpp"

namespace servoloop::sim_common {

// Deeper than this below z = 0 at the start gets the warning.
inline constexpr double kGroundPenetrationWarningDepth_m = 0.01;

// Logs one warning when `link` starts more than the depth above below the
// floor: "<source>: link 'foot' starts 0.230 m below the ground plane ...;
// Spawn it higher: a root z of at least ... m ...". Non-real-time.
void warnIfStartsBelowGround(const urdf::ModelInterface& model, const SimSettings& settings,
                             const std::string& source_name, const std::string& link, double depth_m);

}  // namespace servoloop::sim_common
