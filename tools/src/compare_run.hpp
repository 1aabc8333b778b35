#pragma once
// One headless run of a launch file on one simulation backend, in this
// process (the Node class, no IPC sockets, free-running), capturing the joint
// states of every robot for `servoloop compare`. Non-real-time.
#include <filesystem>
#include <string>
#include <vector>

#include "compare_trajectory.hpp"
#include "servoloop/node/launch_file.hpp"
#include "servoloop/node/run_summary.hpp"

namespace servoloop::cli {

struct BackendRunRequest {
  // The launch file with the command line's publications applied; its own
  // record: and plot: entries are ignored (a comparison writes no CSV).
  servoloop::node::LaunchFile launch;
  std::string backend;  // robot_hw plugin type
  double duration_s = 10.0;
  // sensor_msgs/JointState topics to capture; empty: every robot's
  // <namespace>/joint_states.
  std::vector<std::string> topics;
  std::vector<std::filesystem::path> plugin_directories;
};

struct BackendRun {
  std::string backend;
  servoloop::node::RunSummary summary;
  std::vector<JointTrajectory> trajectories;  // one per topic, in request order
};

// Runs the launch file for duration_s simulated seconds. Throws
// servoloop::ConfigError / servoloop::Error from the launch (bad backend, URDF,
// YAML), and servoloop::Error naming the topic when a topic to capture is
// under no robot's namespace or carries another message type.
BackendRun runOnBackend(const BackendRunRequest& request);

// The robot_hw plugin types on the plugin path (sorted).
std::vector<std::string> availableBackends(const std::vector<std::filesystem::path>& plugin_directories);

// Throws servoloop::Error when `backend` is not on the plugin path, listing
// the ones that are; for mujoco it says how to get the backend built.
void requireBackend(const std::string& backend, const std::vector<std::string>& available);

}  // namespace servoloop::cli
