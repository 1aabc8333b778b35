// Benchmark 5: the backends. For one robot, the same number of 1 ms physics
// steps from the same start, three ways:
//   loop/<robot>/raw_mujoco        servoloop's MuJoCo engine (MujocoPhysics) stepped
//                                  by hand with the controllers' law written inline
//                                  (HandWrittenPositionLaw) → setJointEffort →
//                                  step() (qfrc_applied, then one mj_step, RK4)
//   loop/<robot>/servoloop_mujoco  SimulationLoop::runFor on the "mujoco" robot_hw
//                                  plugin, with the robot's JointPositionController(s)
//                                  and a JointStateController at 50 Hz loaded from the
//                                  build's plugin folder, the topic bus delivering:
//                                  exactly benchmark 2's servoloop_bullet on MuJoCo
//   loop/<robot>/raw_bullet        benchmark 2's raw Bullet loop (BulletWorld by hand)
// and the summary prints, from medians of the same run:
//   (a) servoloop_mujoco / raw_mujoco — what the framework adds to MuJoCo;
//   (b) raw_bullet / raw_mujoco       — the two engines' own stepping cost.
// Both raw loops run the same hand-written law (loop_fixtures.hpp), with the
// gains of the robot's controller YAML and the URDF's limits.
//
// Robots: "seed" (the seed's one_dof robot with transmission, setpoint 1.0 rad,
// 10,000 steps) and "chain32" (robots/chain32, one position controller per
// joint, setpoints 0.2·sin(2π·i/16) rad, 2,000 steps), as in benchmark 2.
// One benchmark iteration is one whole episode on a fresh robot, repeated and
// interleaved at random with the other variants.
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "episode_benchmarks.hpp"
#include "loop_fixtures.hpp"
#include "median_reporter.hpp"
#include "raw_mujoco_pd.hpp"

namespace servoloop::bench {
namespace {

const std::vector<RobotCase>& robots() {
  static const std::vector<RobotCase> all = {seedRobot(), chainRobot(false)};
  return all;
}

std::string nameOf(const std::string& robot, const std::string& variant) { return "loop/" + robot + "/" + variant; }

void registerAll() {
  for (const RobotCase& robot : robots()) {
    benchmark::RegisterBenchmark(nameOf(robot.label, "raw_mujoco").c_str(), rawEpisodes<RawMujocoPd>, &robot)
        ->Iterations(1);
    benchmark::RegisterBenchmark(nameOf(robot.label, "servoloop_mujoco").c_str(), servoloopEpisodes, &robot, "mujoco")
        ->Iterations(1);
    benchmark::RegisterBenchmark(nameOf(robot.label, "raw_bullet").c_str(), rawEpisodes<RawBulletPd>, &robot)
        ->Iterations(1);
  }
}

void summary(const MedianTable& table, std::ostream& out) {
  out << "=== Cost per 1 ms physics step (median over repetitions) ===\n";
  for (const auto& name : table.names()) printMedianLine(out, table, name, name);
  out << "\n=== Ratios (same run, medians) ===\n";
  for (const RobotCase& robot : robots()) {
    const std::string raw_mujoco = nameOf(robot.label, "raw_mujoco");
    const std::string full = nameOf(robot.label, "servoloop_mujoco");
    const std::string raw_bullet = nameOf(robot.label, "raw_bullet");
    if (!table.has(raw_mujoco) || !table.has(full) || !table.has(raw_bullet)) continue;
    printRatioLine(out, table, full, raw_mujoco, robot.label + ": (a) servoloop+mujoco / raw mujoco");
    printRatioLine(out, table, raw_bullet, raw_mujoco, robot.label + ": (b) raw bullet / raw mujoco");
    const double overhead_ns =
        table.median(full, Clock::thread_cpu) - table.median(raw_mujoco, Clock::thread_cpu);
    char line[256];
    std::snprintf(line, sizeof line, "  %-44s %8.0f ns/step over raw mujoco (thread CPU); free-running RTF %.0f\n",
                  (robot.label + ": framework overhead").c_str(), overhead_ns,
                  kTimeStepS / (table.median(full, Clock::wall) * 1e-9));
    out << line;
  }
}

}  // namespace
}  // namespace servoloop::bench

int main(int argc, char** argv) {
  servoloop::bench::registerAll();
  return servoloop::bench::runWithSummary(
      argc, argv, {"--benchmark_repetitions=21", "--benchmark_enable_random_interleaving=true"},
      servoloop::bench::summary);
}
