#pragma once
// The ROS 1 bridge program (servoloop_ros1_bridge, beside the servoloop
// executable; built only where Debian's ROS 1 packages are installed), and the
// bridges a launch starts for its robots (`ros1_bridge: true` in the launch
// file, or `servoloop launch --ros1-bridge`). docs/ros1.md.
#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

namespace servoloop::cli {

// The bridge program's path; throws servoloop::Error saying how to get it when
// this build has none.
std::filesystem::path ros1BridgeProgram();

// Where the build keeps the generated Python message packages the ROS tools
// need (PYTHONPATH).
std::filesystem::path ros1PythonPath();

// Bridges started as child processes, one per robot namespace; stopped
// (SIGINT, then SIGKILL after 15 s) when this object goes. A bridge that ends
// on its own leaves the node running.
class Ros1BridgeProcesses {
 public:
  Ros1BridgeProcesses() = default;
  ~Ros1BridgeProcesses();
  Ros1BridgeProcesses(const Ros1BridgeProcesses&) = delete;
  Ros1BridgeProcesses& operator=(const Ros1BridgeProcesses&) = delete;

  void start(const std::string& robot_namespace);
  // Stops every bridge started (also done by the destructor).
  void stop();

 private:
  std::vector<pid_t> children_;
};

}  // namespace servoloop::cli
