#include "servoloop/node/sdf_world_launch.hpp"

#include <fmt/format.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/core/time.hpp"
#include "servoloop/description/sdf_world.hpp"

namespace servoloop::node {
namespace fs = std::filesystem;

void addSdfWorld(const fs::path& file, WorldSettings& world, std::vector<RobotSpec>& robots,
                 const GivenWorldSettings& given) {
  const fs::path absolute = fs::absolute(file).lexically_normal();
  SdfWorld sdf = readSdfWorld(absolute);
  for (const std::string& warning : sdf.warnings) logger().warn("{}", warning);
  if (sdf.time_step_s && !given.time_step) {
    if (!(*sdf.time_step_s >= kMinTimeStepS && *sdf.time_step_s <= kMaxTimeStepS)) {
      throw ConfigError(fmt::format("{}: <physics><max_step_size> {} s is outside servoloop's range ({} to {} s)",
                                    absolute.string(), *sdf.time_step_s, kMinTimeStepS, kMaxTimeStepS));
    }
    world.time_step_s = *sdf.time_step_s;
  }
  if (!given.gravity) world.gravity = sdf.gravity;
  if (!given.ground_plane) world.ground_plane = sdf.ground_plane;
  std::vector<RobotSpec> models;
  for (SdfWorldModel& model : sdf.models) {
    RobotSpec robot;
    robot.urdf = absolute;
    robot.description = std::move(model.urdf);
    robot.model = model.name;
    robot.robot_namespace = "/" + model.name;
    robot.fixed_base = model.fixed_base;
    robot.pose = model.pose;
    models.push_back(std::move(robot));
  }
  robots.insert(robots.begin(), std::make_move_iterator(models.begin()), std::make_move_iterator(models.end()));
}

LaunchFile loadSdfWorldLaunch(const fs::path& file) {
  LaunchFile launch;
  launch.source = fs::absolute(file).lexically_normal();
  addSdfWorld(file, launch.world, launch.robots);
  return launch;
}

}  // namespace servoloop::node
