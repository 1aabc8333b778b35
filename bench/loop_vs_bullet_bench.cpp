// Benchmark 2: the whole servoloop simulation loop against raw Bullet.
//
// For one robot, the same number of 1 ms physics steps from the same initial
// state, three ways:
//   loop/<robot>/raw_bullet       BulletWorld alone, with the robot's position
//                                 controllers' law written inline
//                                 (HandWrittenPositionLaw: PID + ros_control effort
//                                 saturation) → setJointEffort → step()
//   loop/<robot>/servoloop_bullet SimulationLoop::runFor on the "bullet" robot_hw plugin:
//                                 read (engine joint state; the actuator state through
//                                 the URDF transmissions), ControllerManager::update with the robot's
//                                 effort_controllers/JointPositionController(s) and a
//                                 JointStateController at 50 Hz (plugins from the build),
//                                 write (joint limits, joints → actuators → applied
//                                 efforts), physics step; the topic bus's delivery thread
//                                 running, as in a node
//   loop/<robot>/servoloop_mock   the same on the "mock" backend (no physics engine):
//                                 the framework's own cost, for reference
// The raw loop runs the law and limits of the servoloop controllers with the
// same gains, so both follow the same trajectory and Bullet does the same
// work; the ratio is the framework's cost.
//
// Robots: "seed" — the seed's one_dof robot with its controller YAML, setpoint
// 1.0 rad; "chain32" — robots/chain32 with one position controller per joint,
// and "chain32_group" — the same with one JointGroupPositionController;
// setpoints 0.2·sin(2π·i/16) rad.
//
// One benchmark iteration is one whole episode (a fresh robot, then N steps),
// repeated and interleaved at random with the other variants; the summary
// prints ratios of medians from the same run.
//
//   loop/<robot>/paired           three times, one raw_bullet and one servoloop_bullet
//                                 episode back to back (which goes first alternates), each timed
//                                 on the thread's CPU clock: one ratio per pair. A
//                                 change in the machine's speed that is slower than a
//                                 pair (about 30 ms for the seed) cancels out of each
//                                 ratio; the summary prints their median and quartiles.
#include <time.h>

#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_support.hpp"
#include "episode_benchmarks.hpp"
#include "loop_fixtures.hpp"
#include "median_reporter.hpp"

namespace servoloop::bench {
namespace {

const std::vector<RobotCase>& robots() {
  static const std::vector<RobotCase> all = {seedRobot(), chainRobot(false), chainRobot(true)};
  return all;
}

double threadCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// Thread CPU seconds of one episode on a fresh robot (set-up not counted).
double rawEpisodeSeconds(const RobotCase& robot) {
  const HeapPlacementShuffle placement;
  RawBulletPd raw(robot);
  raw.stepWithoutControl();
  const double start = threadCpuSeconds();
  for (std::uint64_t k = 0; k < robot.steps_per_episode; ++k) raw.step();
  return threadCpuSeconds() - start;
}

double servoloopEpisodeSeconds(const RobotCase& robot) {
  const HeapPlacementShuffle placement;
  ServoloopSimulation simulation(robot, "bullet");
  const double start = threadCpuSeconds();
  simulation.runSteps(robot.steps_per_episode);
  return threadCpuSeconds() - start;
}

// Per robot: servoloop / raw thread CPU time of each back-to-back pair.
std::map<std::string, std::vector<double>>& pairedRatios() {
  static std::map<std::string, std::vector<double>> ratios;
  return ratios;
}

void pairedEpisodes(benchmark::State& state, const RobotCase* robot, const RobotCase* raw_robot) {
  constexpr int kPairsPerRepetition = 3;
  std::vector<double>& ratios = pairedRatios()[robot->label];
  for (auto _ : state) {
    for (int pair = 0; pair < kPairsPerRepetition; ++pair) {
      const bool raw_first = ratios.size() % 2 == 0;
      const double first = raw_first ? rawEpisodeSeconds(*raw_robot) : servoloopEpisodeSeconds(*robot);
      const double second = raw_first ? servoloopEpisodeSeconds(*robot) : rawEpisodeSeconds(*raw_robot);
      ratios.push_back(raw_first ? second / first : first / second);
    }
  }
  state.counters[kUnitsPerIterationCounter] = 2.0 * kPairsPerRepetition * static_cast<double>(robot->steps_per_episode);
}

std::string nameOf(const RobotCase& robot, const std::string& variant) { return "loop/" + robot.label + "/" + variant; }

void registerAll() {
  for (const RobotCase& robot : robots()) {
    if (robot.group_controller.empty()) {
      benchmark::RegisterBenchmark(nameOf(robot, "raw_bullet").c_str(), rawEpisodes<RawBulletPd>, &robot)
          ->Iterations(1);
    }
    benchmark::RegisterBenchmark(nameOf(robot, "servoloop_bullet").c_str(), servoloopEpisodes, &robot, "bullet")
        ->Iterations(1);
    benchmark::RegisterBenchmark(nameOf(robot, "servoloop_mock").c_str(), servoloopEpisodes, &robot, "mock")
        ->Iterations(1);
    // The group robot's raw loop is the chain's (the same law per joint).
    const RobotCase* raw_robot = robot.group_controller.empty() ? &robot : &robots()[1];
    benchmark::RegisterBenchmark(nameOf(robot, "paired").c_str(), pairedEpisodes, &robot, raw_robot)->Iterations(1);
  }
}

void summary(const MedianTable& table, std::ostream& out) {
  // First: it needs no other benchmark (a run of the paired ones alone, as
  // bench/guard/bench_guard.py runs them, still prints it).
  out << "=== Paired ratios: servoloop+bullet / raw bullet, back-to-back episodes (thread CPU) ===\n";
  for (const auto& [robot, ratios] : pairedRatios()) {
    if (ratios.empty()) continue;
    const double median = quantileOf(ratios, 0.5);
    char line[256];
    std::snprintf(line, sizeof line, "  %-44s %6.3f median of %zu pairs (quartiles %.3f, %.3f)   target <= 1.1: %s\n",
                  (robot + ": paired").c_str(), median, ratios.size(), quantileOf(ratios, 0.25),
                  quantileOf(ratios, 0.75), median <= 1.10 ? "met" : "NOT met");
    out << line;
  }
  out << "\n";
  out << "=== Cost per 1 ms physics step (median over repetitions) ===\n";
  for (const auto& name : table.names()) {
    // A pair's own benchmark time includes building both robots: not a cost per step.
    if (!name.ends_with("/paired")) printMedianLine(out, table, name, name);
  }
  out << "\n=== Ratios (same run, medians) ===\n";
  const char* raw_of[][2] = {{"seed", "seed"}, {"chain32", "chain32"}, {"chain32_group", "chain32"}};
  for (const auto& [robot, raw_robot] : raw_of) {
    const std::string raw = std::string("loop/") + raw_robot + "/raw_bullet";
    const std::string full = std::string("loop/") + robot + "/servoloop_bullet";
    const std::string mock = std::string("loop/") + robot + "/servoloop_mock";
    printRatioLine(out, table, full, raw, std::string(robot) + ": servoloop+bullet / raw bullet", 1.10);
    printRatioLine(out, table, mock, raw, std::string(robot) + ": servoloop+mock / raw bullet");
    const double overhead_ns = table.median(full, Clock::thread_cpu) - table.median(raw, Clock::thread_cpu);
    const double rtf = kTimeStepS / (table.median(full, Clock::wall) * 1e-9);
    char line[256];
    std::snprintf(line, sizeof line,
                  "  %-44s %8.0f ns/step over raw (thread CPU); servoloop+mock costs %8.0f ns/step; "
                  "free-running RTF %.0f\n",
                  (std::string(robot) + ": framework overhead").c_str(), overhead_ns,
                  table.median(mock, Clock::thread_cpu), rtf);
    out << line;
  }
}

}  // namespace
}  // namespace servoloop::bench

// The raw side of the node's whole-process comparison (scripts/bench_node.sh,
// part 3): `--raw-process STEPS` loads the seed robot, builds its Bullet world
// with its collision shapes and steps it STEPS times under the position law
// written out (RawBulletPd), then exits. It prints the joint's last position.
int rawProcess(const char* steps_text) {
  using namespace servoloop::bench;
  const auto steps = static_cast<std::uint64_t>(std::stoull(steps_text));
  RawBulletPd raw(seedRobot());
  raw.stepWithoutControl();
  for (std::uint64_t n = 1; n < steps; ++n) raw.step();
  std::printf("%.6f\n", raw.jointPosition(0));
  return 0;
}

int main(int argc, char** argv) {
  if (argc == 3 && std::string(argv[1]) == "--raw-process") return rawProcess(argv[2]);
  servoloop::bench::registerAll();
  return servoloop::bench::runWithSummary(
      argc, argv, {"--benchmark_repetitions=21", "--benchmark_enable_random_interleaving=true"},
      servoloop::bench::summary);
}
