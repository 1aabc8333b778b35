#include "bench_support.hpp"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <utility>

#include "servoloop/controller_manager/controller_base.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/node/launch_file.hpp"
#include "servoloop/node/node.hpp"

namespace servoloop::bench {

namespace hi = hardware_interface;
namespace cm = controller_manager;

BenchJointsHW::BenchJointsHW(std::vector<std::string> joint_names)
    : position(joint_names.size(), 0.0),
      velocity(joint_names.size(), 0.0),
      effort(joint_names.size(), 0.0),
      effort_command(joint_names.size(), 0.0),
      velocity_command(joint_names.size(), 0.0),
      names_(std::move(joint_names)) {
  for (std::size_t i = 0; i < names_.size(); ++i) {
    hi::JointStateHandle state(names_[i], &position[i], &velocity[i], &effort[i]);
    state_interface_.registerHandle(state);
    effort_interface_.registerHandle(hi::JointHandle(state, &effort_command[i]));
    velocity_interface_.registerHandle(hi::JointHandle(state, &velocity_command[i]));
  }
  registerInterface(&state_interface_);
  registerInterface(&effort_interface_);
  registerInterface(&velocity_interface_);
}

PluginControllerFactory::PluginControllerFactory() : loader_({pluginDirectory()}) {}

cm::ControllerPtr PluginControllerFactory::create(const std::string& type) {
  if (!loader_.hasType(type)) return {};
  auto plugin = loader_.create<cm::ControllerBase>(type);
  servoloop::plugin::PluginDeleter deleter = plugin.get_deleter();
  return cm::ControllerPtr(plugin.release(), [deleter](cm::ControllerBase* c) { deleter(c); });
}

std::vector<std::string> PluginControllerFactory::types() {
  std::vector<std::string> names;
  for (const auto& info : loader_.listTypes(cm::ControllerBase::kPluginKind)) names.push_back(info.type);
  return names;
}

std::filesystem::path pluginDirectory() { return SERVOLOOP_PLUGIN_DIR; }

std::string sourcePath(const std::string& relative) { return std::string(SERVOLOOP_SOURCE_DIR) + "/" + relative; }

std::string readTextFile(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw Error("cannot read '" + path + "'");
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

std::vector<std::string> numberedJointNames(std::size_t joints) {
  std::vector<std::string> names;
  for (std::size_t i = 1; i <= joints; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "joint_%02zu", i);
    names.emplace_back(name);
  }
  return names;
}

HeapPlacementShuffle::HeapPlacementShuffle() {
  static std::mt19937 generator{std::random_device{}()};
  constexpr std::size_t kStep = 64;
  constexpr std::size_t kMaxSteps = 256;
  const std::size_t steps = std::uniform_int_distribution<std::size_t>(1, kMaxSteps)(generator);
  block_.assign(steps * kStep, 1);  // written, so the pages are really there
}

std::string revoluteChainUrdf(std::size_t joints) {
  const auto names = numberedJointNames(joints);
  std::string xml = R"(<?xml version="1.0"?><robot name="bench_chain"><link name="world"/>)";
  std::string parent = "world";
  for (std::size_t i = 0; i < joints; ++i) {
    const std::string link = "link_" + names[i].substr(6);
    xml += "<link name=\"" + link +
           "\"><inertial><origin xyz=\"0 0 0.05\"/><mass value=\"1\"/>"
           "<inertia ixx=\"0.001\" ixy=\"0\" ixz=\"0\" iyy=\"0.001\" iyz=\"0\" izz=\"0.001\"/></inertial></link>";
    xml += "<joint name=\"" + names[i] + "\" type=\"revolute\"><parent link=\"" + parent + "\"/><child link=\"" +
           link +
           "\"/><origin xyz=\"0 0 0.1\"/><axis xyz=\"0 1 0\"/>"
           "<limit lower=\"-2\" upper=\"2\" effort=\"100\" velocity=\"10\"/></joint>";
    parent = link;
  }
  return xml + "</robot>";
}

namespace {
double clockSeconds(clockid_t clock) {
  timespec now{};
  clock_gettime(clock, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}
}  // namespace

RunTimer::RunTimer()
    : wall_start_s_(clockSeconds(CLOCK_MONOTONIC)), cpu_start_s_(clockSeconds(CLOCK_PROCESS_CPUTIME_ID)) {}

RunTimes RunTimer::elapsed() const {
  const double cpu = clockSeconds(CLOCK_PROCESS_CPUTIME_ID);
  const double wall = clockSeconds(CLOCK_MONOTONIC);
  return {wall - wall_start_s_, cpu - cpu_start_s_};
}

RunTimes timesOfNodeRun(const std::string& launch_yaml, const std::filesystem::path& dir, double duration_s) {
  node::NodeOptions options;
  options.serve_ipc = false;
  options.real_time_factor = 0.0;
  options.duration_s = duration_s;
  node::Node node(node::parseLaunchFile(launch_yaml, "bench", dir), options);
  const RunTimer timer;
  node.start();
  node.waitUntilDone({}, std::chrono::milliseconds(5));
  const RunTimes times = timer.elapsed();
  node.shutdown();
  return times;
}

double wallSecondsOfNodeRun(const std::string& launch_yaml, const std::filesystem::path& dir, double duration_s) {
  return timesOfNodeRun(launch_yaml, dir, duration_s).wall_s;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

}  // namespace servoloop::bench
