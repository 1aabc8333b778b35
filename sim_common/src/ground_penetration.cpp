#include "servoloop/sim_common/ground_penetration.hpp"

#include "servoloop/core/logging.hpp"

namespace servoloop::sim_common {

void warnIfStartsBelowGround(const urdf::ModelInterface& model, const SimSettings& settings,
                             const std::string& source_name, const std::string& link, double depth_m) {
  if (!(depth_m > kGroundPenetrationWarningDepth_m)) return;
  (void)model;
  const std::string fix = fmt::format(
      "Spawn it higher: a root z of at least {:.3f} m (launch file: pose: [x, y, z]; spawn-model and roslaunch's "
      "spawn_model: -z), or start the joints elsewhere (<ns>/sim/initial_positions)",
      settings.base_position.z() + depth_m);
  logger().warn(
      "{}: link '{}' starts {:.3f} m below the ground plane (z = 0) at its spawn pose and start positions; the "
      "contacts push it out with a jolt at the first step (a free-standing robot is thrown up). {}, or take the "
      "floor away (world: ground_plane: false)",
      source_name, link, depth_m, fix);
}

}  // namespace servoloop::sim_common
