#pragma once
// An SDFormat world (description/sdf_world.hpp) in a launch: its settings
// into the launch's world, its models as robots (objects: no controllers),
// its warnings logged. Used by `servoloop launch my.world`, by a YAML launch
// file's `world: {file: my.world}` and by a ROS launch file including
// gazebo_ros's empty_world.launch with a world_name.
#include <filesystem>
#include <vector>

#include "servoloop/node/launch_file.hpp"

namespace servoloop::node {

// Which world settings the launch file gave itself (those stay as given).
struct GivenWorldSettings {
  bool time_step = false;
  bool gravity = false;
  bool ground_plane = false;
};

// Reads `file` and puts its settings into `world` (except those `given`) and
// its models at the front of `robots`. Throws ConfigError as readSdfWorld
// does, and for a physics step outside servoloop's range.
void addSdfWorld(const std::filesystem::path& file, WorldSettings& world, std::vector<RobotSpec>& robots,
                 const GivenWorldSettings& given = {});

// `servoloop launch my.world`: a launch file of that world alone.
LaunchFile loadSdfWorldLaunch(const std::filesystem::path& file);

}  // namespace servoloop::node
