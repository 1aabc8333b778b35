#pragma once
// What Gazebo leaves out of a URDF it cannot simulate, servoloop leaves out too:
// the loaders take a robot description the way gazebo_ros_control does, with
// one warning per thing skipped instead of refusing the robot.
// Non-real-time (parses XML, allocates, logs).
#include <string>
#include <vector>

namespace servoloop {

struct SimulatableUrdf {
  std::string xml;                          // the description to load (the input when nothing was left out)
  std::vector<std::string> skipped_links;   // in document order
  std::vector<std::string> skipped_joints;
  std::vector<std::string> skipped_transmissions;
};

// Leaves out every link moved by a non-fixed joint whose rigid body (the link
// and the links fixed below it) has no mass — no <inertial>, or masses summing
// to <= 0 — together with that joint, every link and joint below it, and the
// <transmission> elements naming a joint left out. Gazebo's URDF import drops
// such links and their children the same way. Each left-out link gets one
// warning naming `source_name`, the link, its joint, what goes with it and the
// fix. A description that is not well-formed XML or whose links do not form a
// tree is returned unchanged (parseRobotModel reports what is wrong with it).
SimulatableUrdf simulatableUrdf(const std::string& xml, const std::string& source_name);

}  // namespace servoloop
