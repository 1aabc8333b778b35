// Benchmark 1: the controller manager's cost per control cycle.
//
// ControllerManager::update at 1 kHz on a RobotHW whose read/write do nothing
// (BenchJointsHW), running a joint_state_controller/JointStateController and
// effort_controllers position controllers loaded from the build's plugin
// folder, as a node loads them. The position controllers get a new setpoint
// every kCyclesPerCommand cycles, published on the topic bus from the
// benchmark thread with the timer paused (publishing is the non-real-time
// side's work). The bus's delivery thread is not started: the joint state
// and controller state publishers then find their queue full and recycle the
// oldest slot, which costs the same as taking a free one, and the benchmark
// stays single-threaded.
//
// Variants (ns per cycle, against the number of joints N):
//   manager/empty                         no controller: the manager's own cost
//   manager/joint_states_only/<rate>      the JointStateController alone
//   manager/per_joint/<rate>/joints:N     JointStateController + N JointPositionControllers
//   manager/per_joint_timed/jsc_50Hz/joints:N  the same with the controllers' updates timed as the
//                                         node's loops time them (`servoloop control stats`): one
//                                         cycle in ControlLoop::kUpdateTimingStride (16) reads the
//                                         cycle clock once per controller; a bare manager, the
//                                         other variants, times nothing
//   manager/group/<rate>/joints:N         JointStateController + one JointGroupPositionController
//   manager/diff_drive/jsc_50Hz/joints:2  JointStateController + a DiffDriveController on two wheels
//                                         (limits on, odom and tf at 50 Hz, a new cmd_vel each second)
//   manager/trajectory/<rate>/joints:N    JointStateController + one effort JointTrajectoryController
//                                         (state at 50 Hz) always mid-trajectory: a new 20-point
//                                         quintic trajectory over 2 s replaces the old one every
//                                         second, so each cycle samples a segment and runs N PIDs
// <rate> is the JointStateController's publish_rate: jsc_50Hz (the seed's,
// publishing every 20th cycle) or jsc_every_cycle (1000 Hz).
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <yaml-cpp/yaml.h>

#include "bench_support.hpp"
#include "median_reporter.hpp"
#include "servoloop/controller_manager/control_loop.hpp"
#include "servoloop/controller_manager/controller_manager.hpp"
#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/description/robot_model.hpp"

namespace servoloop::bench {
namespace {

namespace cm = controller_manager;

constexpr double kManagerRateHz = 1000.0;
constexpr std::uint64_t kCyclesPerCommand = 1000;  // one new setpoint per second of control time
constexpr const char* kNamespace = "/bench";

enum class PositionControllers { none, per_joint, group, trajectory, diff_drive };

// The seed's PID gains (robots/one_dof/control_config/one_dof_ctl_params.yaml).
YAML::Node seedPid() { return YAML::Load("{p: 10.0, i: 10.0, d: 10.0, i_clamp_min: -10.0, i_clamp_max: 10.0}"); }

// A controller manager on BenchJointsHW with its controllers loaded and started.
class ManagerUnderTest {
 public:
  ManagerUnderTest(std::size_t joints, PositionControllers layout, double joint_state_rate_hz)
      : hw_(numberedJointNames(joints)) {
    YAML::Node params;
    std::vector<std::string> controllers;
    if (joint_state_rate_hz > 0.0) {
      params["joint_state_controller"]["type"] = "joint_state_controller/JointStateController";
      params["joint_state_controller"]["publish_rate"] = joint_state_rate_hz;
      controllers.push_back("joint_state_controller");
    }
    const auto& names = hw_.jointNames();
    if (layout == PositionControllers::per_joint) {
      for (const auto& joint : names) {
        const std::string name = joint + "_position_controller";
        params[name]["type"] = "effort_controllers/JointPositionController";
        params[name]["joint"] = joint;
        params[name]["pid"] = seedPid();
        controllers.push_back(name);
        command_topics_.push_back(std::string(kNamespace) + "/" + name + "/command");
      }
    } else if (layout == PositionControllers::group) {
      const std::string name = "group_position_controller";
      params[name]["type"] = "effort_controllers/JointGroupPositionController";
      for (const auto& joint : names) {
        params[name]["joints"].push_back(joint);
        params[name][joint]["pid"] = seedPid();
      }
      controllers.push_back(name);
      group_command_topic_ = std::string(kNamespace) + "/" + name + "/command";
      group_command_.data.assign(names.size(), 0.0);
    } else if (layout == PositionControllers::trajectory) {
      const std::string name = "arm_controller";
      params[name]["type"] = "effort_controllers/JointTrajectoryController";
      for (const auto& joint : names) {
        params[name]["joints"].push_back(joint);
        params[name]["gains"][joint] = YAML::Load("{p: 100.0, d: 10.0, i: 1.0, i_clamp: 1.0}");
      }
      controllers.push_back(name);
      trajectory_topic_ = std::string(kNamespace) + "/" + name + "/command";
      trajectory_.joint_names = names;
      for (int i = 1; i <= 20; ++i) {
        servoloop::trajectory_msgs::JointTrajectoryPoint point;
        point.positions.assign(names.size(), 0.0);
        point.velocities.assign(names.size(), 0.0);
        point.accelerations.assign(names.size(), 0.0);
        point.time_from_start = 0.1 * i;
        trajectory_.points.push_back(point);
      }
    }

    if (layout == PositionControllers::diff_drive) {
      // Two wheels (the first two joints), limits on, odom and tf at 50 Hz.
      const std::string name = "base_controller";
      params[name] = YAML::Load(
          "{type: diff_drive_controller/DiffDriveController, wheel_separation: 0.4, wheel_radius: 0.05, "
          "cmd_vel_timeout: 2.0, linear: {x: {has_velocity_limits: true, max_velocity: 1.0, "
          "has_acceleration_limits: true, max_acceleration: 2.0}}, angular: {z: {has_velocity_limits: true, "
          "max_velocity: 2.0}}}");
      params[name]["left_wheel"] = names.at(0);
      params[name]["right_wheel"] = names.at(1);
      controllers.push_back(name);
      twist_topic_ = std::string(kNamespace) + "/" + name + "/cmd_vel";
    }

    cm::ControllerContext context;
    context.robot_namespace = kNamespace;
    context.topics = &bus_;
    context.robot_model = parseRobotModel(revoluteChainUrdf(joints), "bench_chain.urdf");
    manager_ = std::make_unique<cm::ControllerManager>(&hw_, std::make_shared<PluginControllerFactory>(),
                                                       cm::ControllerManager::lookupIn(params), context,
                                                       kManagerRateHz);
    for (const auto& name : controllers) {
      if (auto result = manager_->loadController(name); !result) throw std::runtime_error(result.message);
    }
    cm::SwitchRequest request;
    request.start_controllers = controllers;
    if (auto result = manager_->requestSwitch(request); !result) throw std::runtime_error(result.message);
    cycle();  // carries out the switch
    if (manager_->switchPending()) throw std::runtime_error("the controller switch did not happen");
  }

  ~ManagerUnderTest() { manager_.reset(); }

  // Real-time: one control cycle.
  void cycle() noexcept {
    ++cycles_;
    manager_->update(Time(static_cast<double>(cycles_) / kManagerRateHz), Duration(1.0 / kManagerRateHz));
  }

  // Non-real-time: a new setpoint for every position controller.
  void sendCommands(double setpoint_rad) {
    for (const auto& topic : command_topics_) bus_.publish(topic, servoloop::std_msgs::Float64{setpoint_rad});
    if (!group_command_topic_.empty()) {
      for (double& value : group_command_.data) value = setpoint_rad;
      bus_.publish(group_command_topic_, group_command_);
    }
    if (!twist_topic_.empty()) {
      servoloop::geometry_msgs::Twist twist;
      twist.linear.x = setpoint_rad;
      twist.angular.z = -setpoint_rad;
      bus_.publish(twist_topic_, twist);
    }
    if (!trajectory_topic_.empty()) {
      // Points of a sine over the 2 s, with their velocities and accelerations.
      for (std::size_t i = 0; i < trajectory_.points.size(); ++i) {
        auto& point = trajectory_.points[i];
        const double t = point.time_from_start;
        for (std::size_t j = 0; j < point.positions.size(); ++j) {
          point.positions[j] = setpoint_rad * std::sin(t);
          point.velocities[j] = setpoint_rad * std::cos(t);
          point.accelerations[j] = -setpoint_rad * std::sin(t);
        }
      }
      bus_.publish(trajectory_topic_, trajectory_);
      bus_.flush();  // the controller builds the trajectory on the delivery side
    }
  }

  void setUpdateTiming(bool timed) noexcept { manager_->setUpdateTiming(timed); }

  // The effort the first joint is commanded (read after the timed loop).
  double firstEffortCommand() const { return hw_.effort_command.front(); }

 private:
  servoloop::realtime::TopicBus bus_;
  BenchJointsHW hw_;
  std::unique_ptr<cm::ControllerManager> manager_;
  std::vector<std::string> command_topics_;
  std::string group_command_topic_;
  servoloop::std_msgs::Float64MultiArray group_command_;
  std::string trajectory_topic_;
  servoloop::trajectory_msgs::JointTrajectory trajectory_;
  std::string twist_topic_;
  std::uint64_t cycles_ = 0;
};

void runManager(benchmark::State& state, PositionControllers layout, double joint_state_rate_hz, bool timed) {
  const auto joints = static_cast<std::size_t>(state.range(0));
  ManagerUnderTest manager(joints, layout, joint_state_rate_hz);
  std::uint64_t cycle = 0;
  for (auto _ : state) {
    if (++cycle % kCyclesPerCommand == 0) {
      state.PauseTiming();
      manager.sendCommands((cycle / kCyclesPerCommand) % 2 == 0 ? 0.5 : -0.5);
      state.ResumeTiming();
    }
    if (timed) manager.setUpdateTiming(cycle % cm::ControlLoop::kUpdateTimingStride == 1);
    manager.cycle();
  }
  benchmark::DoNotOptimize(manager.firstEffortCommand());
  state.counters["joints"] = static_cast<double>(joints);
}

void managerUpdate(benchmark::State& state, PositionControllers layout, double joint_state_rate_hz) {
  runManager(state, layout, joint_state_rate_hz, false);
}

void managerUpdateTimed(benchmark::State& state, PositionControllers layout, double joint_state_rate_hz) {
  runManager(state, layout, joint_state_rate_hz, true);
}

struct RateVariant {
  const char* label;
  double publish_rate_hz;
};
constexpr RateVariant kRates[] = {{"jsc_50Hz", 50.0}, {"jsc_every_cycle", kManagerRateHz}};

void registerAll() {
  benchmark::RegisterBenchmark("manager/empty", managerUpdate, PositionControllers::none, 0.0)
      ->Arg(1)
      ->ArgName("joints");
  for (const auto& rate : kRates) {
    const std::string suffix = std::string("/") + rate.label;
    benchmark::RegisterBenchmark(("manager/joint_states_only" + suffix).c_str(), managerUpdate,
                                 PositionControllers::none, rate.publish_rate_hz)
        ->Arg(1)
        ->Arg(8)
        ->Arg(64)
        ->ArgName("joints");
    auto* per_joint = benchmark::RegisterBenchmark(("manager/per_joint" + suffix).c_str(), managerUpdate,
                                                   PositionControllers::per_joint, rate.publish_rate_hz);
    per_joint->Arg(1)->Arg(8)->Arg(64)->ArgName("joints");
    if (rate.publish_rate_hz == 50.0) {
      per_joint->Arg(2)->Arg(4)->Arg(16)->Arg(32);  // for the slope fit
      benchmark::RegisterBenchmark(("manager/per_joint_timed" + suffix).c_str(), managerUpdateTimed,
                                   PositionControllers::per_joint, rate.publish_rate_hz)
          ->Arg(1)->Arg(2)->Arg(4)->Arg(8)->Arg(16)->Arg(32)->Arg(64)
          ->ArgName("joints");
    }
    benchmark::RegisterBenchmark(("manager/group" + suffix).c_str(), managerUpdate, PositionControllers::group,
                                 rate.publish_rate_hz)
        ->Arg(1)
        ->Arg(8)
        ->Arg(64)
        ->ArgName("joints");
    benchmark::RegisterBenchmark(("manager/trajectory" + suffix).c_str(), managerUpdate,
                                 PositionControllers::trajectory, rate.publish_rate_hz)
        ->Arg(1)
        ->Arg(6)
        ->Arg(64)
        ->ArgName("joints");
    if (rate.publish_rate_hz == 50.0) {
      benchmark::RegisterBenchmark(("manager/group" + suffix).c_str(), managerUpdate, PositionControllers::group,
                                   rate.publish_rate_hz)
          ->Arg(6)
          ->ArgName("joints");
      benchmark::RegisterBenchmark(("manager/diff_drive" + suffix).c_str(), managerUpdate,
                                   PositionControllers::diff_drive, rate.publish_rate_hz)
          ->Arg(2)
          ->ArgName("joints");
    }
  }
}

std::string nameOf(const std::string& family, std::size_t joints) {
  return family + "/joints:" + std::to_string(joints);
}

// Least-squares slope and intercept of the median ns/cycle against joints.
void printFit(std::ostream& out, const MedianTable& table, const std::string& family) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t joints : {1, 2, 4, 8, 16, 32, 64}) {
    if (!table.has(nameOf(family, joints))) continue;
    const double x = static_cast<double>(joints);
    const double y = table.median(nameOf(family, joints), Clock::thread_cpu);
    n += 1;
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  if (n < 2) return;
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  const double intercept = (sy - slope * sx) / n;
  const double endpoints = (table.median(nameOf(family, 64), Clock::thread_cpu) -
                            table.median(nameOf(family, 1), Clock::thread_cpu)) /
                           63.0;
  char line[256];
  std::snprintf(line, sizeof line,
                "  %-36s %6.1f ns/joint (least squares over %d sizes), %6.1f ns/joint ((t64 - t1) / 63), "
                "intercept %6.1f ns\n",
                family.c_str(), slope, static_cast<int>(n), endpoints, intercept);
  out << line;
}

void summary(const MedianTable& table, std::ostream& out) {
  out << "=== Controller manager cost per cycle (median over repetitions, ns/cycle) ===\n";
  for (const auto& name : table.names()) printMedianLine(out, table, name, name);
  out << "\n=== Growth with the number of joints (thread CPU medians) ===\n";
  for (const auto& rate : kRates) {
    printFit(out, table, std::string("manager/per_joint/") + rate.label);
    if (std::string(rate.label) == "jsc_50Hz") printFit(out, table, "manager/per_joint_timed/jsc_50Hz");
    printFit(out, table, std::string("manager/group/") + rate.label);
  }
  out << "\n=== Ratios (same run) ===\n";
  for (const auto& rate : kRates) {
    const std::string per_joint = std::string("manager/per_joint/") + rate.label;
    const std::string group = std::string("manager/group/") + rate.label;
    printRatioLine(out, table, nameOf(per_joint, 64), nameOf(group, 64),
                   std::string("64 per-joint / 1 group, ") + rate.label);
  }
  printRatioLine(out, table, nameOf("manager/per_joint/jsc_every_cycle", 1), nameOf("manager/per_joint/jsc_50Hz", 1),
                 "1 joint, publish every cycle / 50 Hz");
  printRatioLine(out, table, nameOf("manager/trajectory/jsc_50Hz", 6), nameOf("manager/group/jsc_50Hz", 6),
                 "6 joints, trajectory controller mid-trajectory / group position controller");
  const std::string target = nameOf("manager/per_joint/jsc_50Hz", 1);
  const double target_ns = 200.0;
  out << "\nTarget: one joint (JointStateController at 50 Hz + one JointPositionController) < " << target_ns
      << " ns/cycle: median " << table.median(target, Clock::wall) << " ns wall, "
      << table.median(target, Clock::thread_cpu) << " ns thread CPU -> "
      << (table.median(target, Clock::thread_cpu) < target_ns ? "met" : "NOT met") << "\n";
}

}  // namespace
}  // namespace servoloop::bench

int main(int argc, char** argv) {
  servoloop::bench::registerAll();
  return servoloop::bench::runWithSummary(argc, argv,
                                          {"--benchmark_repetitions=15", "--benchmark_enable_random_interleaving=true",
                                           "--benchmark_min_time=0.05"},
                                          servoloop::bench::summary);
}
