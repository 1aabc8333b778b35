#pragma once
// What the servoloop benchmarks share: a RobotHW with plain joint storage, a
// controller factory backed by the build's plugin folder (controllers come to
// the benchmarks exactly as they come to a node), URDF/YAML helpers and paths.
// Everything here is set-up code; none of it runs inside a timed region.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "servoloop/controller_manager/controller_factory.hpp"
#include "servoloop/plugin/plugin_loader.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/hardware_interface/robot_hw.hpp"

namespace servoloop::bench {

// Joints with state storage and an effort and a velocity command each, in joint space.
// read()/write() do nothing: the benchmark measures the controller manager
// alone. Storage never moves after construction.
class BenchJointsHW : public hardware_interface::RobotHW {
 public:
  explicit BenchJointsHW(std::vector<std::string> joint_names);

  void init(const hardware_interface::HardwareInfo&) override {}
  ReturnType read(Time, Duration) override { return ReturnType::ok; }
  ReturnType write(Time, Duration) override { return ReturnType::ok; }

  const std::vector<std::string>& jointNames() const { return names_; }
  // Joint state the controllers see (rad, rad/s, N·m) and what they command (N·m, rad/s).
  std::vector<double> position, velocity, effort, effort_command, velocity_command;

 private:
  std::vector<std::string> names_;
  hardware_interface::JointStateInterface state_interface_;
  hardware_interface::EffortJointInterface effort_interface_;
  hardware_interface::VelocityJointInterface velocity_interface_;
};

// Controllers from the plugin libraries in the build's plugin folder, through
// the same PluginLoader a node uses.
class PluginControllerFactory : public controller_manager::ControllerFactory {
 public:
  PluginControllerFactory();
  controller_manager::ControllerPtr create(const std::string& type) override;
  std::vector<std::string> types() override;

 private:
  servoloop::plugin::PluginLoader loader_;
};

// A heap block of random size (64 B to 16 KiB in steps of 64 B) taken before a
// benchmark builds its robot and held until its episode ends, so that each
// repetition's objects start at a different heap address. The same code runs
// a few percent faster or slower depending on where its hot data happens to
// lie (cache sets, 4 KiB aliasing); without this a process keeps one
// placement for all its repetitions, and the median of a run says as much
// about that placement as about the code. Every variant takes one.
class HeapPlacementShuffle {
 public:
  HeapPlacementShuffle();

 private:
  std::vector<char> block_;
};

// The build's plugin folder (controllers and robot_hw backends).
std::filesystem::path pluginDirectory();
// A path inside the source tree, e.g. "robots/chain32/chain32.urdf".
std::string sourcePath(const std::string& relative);
std::string readTextFile(const std::string& path);

// The wall and CPU seconds of a timed region. CPU is this process's user and
// system time over every thread (CLOCK_PROCESS_CPUTIME_ID): the work done,
// which a busy neighbour on a shared machine stretches far less than it
// stretches the wall time.
struct RunTimes {
  double wall_s = 0.0;
  double cpu_s = 0.0;
};

// Starts timing at construction; elapsed() is the time since.
class RunTimer {
 public:
  RunTimer();
  RunTimes elapsed() const;

 private:
  double wall_start_s_;
  double cpu_start_s_;
};

// Wall and CPU seconds of a node (node::Node as `servoloop launch` builds it)
// of the launch file `launch_yaml` (paths relative to `dir`), free-running for
// `duration_s` simulated seconds; its construction is not counted.
RunTimes timesOfNodeRun(const std::string& launch_yaml, const std::filesystem::path& dir, double duration_s);

// Wall seconds of a node (node::Node as `servoloop launch` builds it) of the
// launch file `launch_yaml` (paths relative to `dir`), free-running for
// `duration_s` simulated seconds; its construction is not counted.
double wallSecondsOfNodeRun(const std::string& launch_yaml, const std::filesystem::path& dir, double duration_s);
// The median of `values` (the upper one of an even count).
double median(std::vector<double> values);

// "joint_01" ... "joint_<n>" (two digits at least).
std::vector<std::string> numberedJointNames(std::size_t joints);

// A serial chain of revolute joints named as numberedJointNames, each with
// limits [-2, 2] rad, 100 N·m, 10 rad/s and a 1 kg link: enough of a robot
// description for the position controllers' limit and wrapping logic.
std::string revoluteChainUrdf(std::size_t joints);

}  // namespace servoloop::bench
