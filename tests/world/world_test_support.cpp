#include "world_test_support.hpp"

#include <fmt/format.h>

#include "temp_dir.hpp"

namespace servoloop::world_test {

std::string boxUrdf(double side, double mass, double mu) {
  const double inertia = mass * side * side / 6.0;
  return fmt::format(R"(<robot name="box">
  <link name="box">
    <inertial><mass value="{m}"/><inertia ixx="{i}" ixy="0" ixz="0" iyy="{i}" iyz="0" izz="{i}"/></inertial>
    <collision><geometry><box size="{s} {s} {s}"/></geometry></collision>
    <visual><geometry><box size="{s} {s} {s}"/></geometry></visual>
  </link>
  <gazebo reference="box"><mu1>{mu}</mu1><mu2>{mu}</mu2></gazebo>
</robot>
)",
                     fmt::arg("m", mass), fmt::arg("i", inertia), fmt::arg("s", side), fmt::arg("mu", mu));
}

fs::path writePushWorld(const fs::path& dir, const std::string& backend, double speed, double drive_until_s,
                        double box_x) {
  const fs::path diff_bot = fs::path(SERVOLOOP_SOURCE_DIR) / "robots" / "diff_bot";
  std::string yaml = fmt::format(R"(world: {{backend: {}, time_step: 0.001, ground_plane: true}}
controller_manager: {{update_rate: 1000}}
robots:
  - urdf: {}
    model: diff_bot
    namespace: /diff_bot
    pose: [0, 0, 0.1, 0, 0, 0]
    params: [{}]
    controllers: [joint_state_controller, diff_drive_controller]
)",
                                 backend, (diff_bot / "diff_bot.urdf").string(),
                                 (diff_bot / "control_config" / "diff_bot_controllers.yaml").string());
  if (box_x > 0.0) {
    testing::writeFile(dir / "box.urdf", boxUrdf(0.2, 1.0, 1.0));
    yaml += fmt::format("  - urdf: box.urdf\n    namespace: /box\n    pose: [{}, 0, 0.1, 0, 0, 0]\n", box_x);
  }
  yaml += "publish:\n";
  for (double t = 0.5; t < drive_until_s + 1e-9; t += 0.25) {
    yaml += fmt::format(
        "  - {{topic: /diff_bot/diff_drive_controller/cmd_vel, type: geometry_msgs/Twist, time: {}, "
        "value: {{linear: {{x: {}}}}}}}\n",
        t, speed);
  }
  const fs::path launch = dir / "push.launch.yaml";
  testing::writeFile(launch, yaml);
  return launch;
}

node::NodeOptions pausedOptions() {
  node::NodeOptions options;
  options.serve_ipc = false;
  options.real_time_factor = 0.0;
  options.start_paused = true;
  return options;
}

GroundTruthWatch::GroundTruthWatch(realtime::TopicBus& bus, const std::string& robot_namespace)
    : subscription_(bus.subscribe<nav_msgs::Odometry>(robot_namespace + "/ground_truth/odom",
                                                      [this](const nav_msgs::Odometry& message) {
                                                        std::lock_guard lock(mutex_);
                                                        latest_ = message;
                                                        received_ = true;
                                                      })) {}

nav_msgs::Odometry GroundTruthWatch::latest() const {
  std::lock_guard lock(mutex_);
  return latest_;
}

bool GroundTruthWatch::received() const {
  std::lock_guard lock(mutex_);
  return received_;
}

}  // namespace servoloop::world_test
