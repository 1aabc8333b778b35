#pragma once
// What the world tests share: the robots they put in one world (the
// project's wheeled base, a free box, the seed arm), written as launch files
// in a test's own folder, and the ground truth of a robot as its bus delivers it.
#include <filesystem>
#include <mutex>
#include <string>

#include "servoloop/node/launch_file.hpp"
#include "servoloop/node/node.hpp"
#include "servoloop/realtime/messages.hpp"
#include "servoloop/realtime/topic_bus.hpp"

namespace servoloop::world_test {

namespace fs = std::filesystem;

// A free box (one link, no joint): side `side` m, mass `mass` kg, contact
// friction `mu`.
std::string boxUrdf(double side, double mass, double mu);

// A world on `backend` with the ground plane: the wheeled base
// (robots/diff_bot, /diff_bot) at the origin facing +x, driven at `speed`
// m/s from t = 0.5 s until `drive_until_s` (cmd_vel every 0.25 s), and, when
// box_x > 0, a free 0.2 m, 1 kg box (/box) resting at x = box_x. Written
// with its files into `dir`; returns the launch file's path.
fs::path writePushWorld(const fs::path& dir, const std::string& backend, double speed, double drive_until_s,
                        double box_x);

// A node for in-process tests: no sockets, free-running, starting paused
// (the test steps it).
node::NodeOptions pausedOptions();

// The latest message of a robot's <ns>/ground_truth/odom, as delivered.
class GroundTruthWatch {
 public:
  GroundTruthWatch(realtime::TopicBus& bus, const std::string& robot_namespace);
  nav_msgs::Odometry latest() const;
  bool received() const;

 private:
  mutable std::mutex mutex_;
  nav_msgs::Odometry latest_;
  bool received_ = false;
  realtime::Subscription subscription_;
};

}  // namespace servoloop::world_test
