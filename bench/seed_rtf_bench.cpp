// Benchmark 3 (in-process form): the headless real-time factor of the seed
// run — what `servoloop launch robots/one_dof/one_dof_w_jnt_ctl.launch.yaml
// --duration 30` does, without the process start-up, launch-file parsing and
// IPC server: the seed robot on the bullet backend, its
// JointStateController (50 Hz) and joint1_position_controller commanded to
// 1.0 rad, SimulationLoop free-running (real_time_factor 0) for 30 s of
// simulated time, the topic bus delivering. Real-time factor = simulated time
// / wall time of the run. Repeated on a fresh robot; prints every run and the
// median.
//
//   servoloop_bench_seed_rtf [--duration SECONDS] [--repetitions N]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "loop_fixtures.hpp"

int main(int argc, char** argv) {
  using namespace servoloop::bench;
  double duration_s = 30.0;
  int repetitions = 5;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--duration") {
      duration_s = std::atof(argv[i + 1]);
    } else if (flag == "--repetitions") {
      repetitions = std::atoi(argv[i + 1]);
    } else {
      std::fprintf(stderr, "usage: %s [--duration SECONDS] [--repetitions N]\n", argv[0]);
      return 2;
    }
  }
  if (!(duration_s > 0.0) || repetitions < 1) {
    std::fprintf(stderr, "--duration must be > 0 and --repetitions >= 1\n");
    return 2;
  }

  const RobotCase seed = seedRobot();
  const auto steps = static_cast<std::uint64_t>(std::llround(duration_s / kTimeStepS));
  std::vector<double> factors;
  for (int run = 0; run < repetitions; ++run) {
    ServoloopSimulation simulation(seed, "bullet");
    const auto start = std::chrono::steady_clock::now();
    simulation.runSteps(steps);
    const std::chrono::duration<double> wall = std::chrono::steady_clock::now() - start;
    const double sim_time_s = static_cast<double>(steps) * kTimeStepS;
    factors.push_back(sim_time_s / wall.count());
    std::printf("run %d: %.1f s simulated in %.3f s wall: real-time factor %.1f (joint1 at %.4f rad)\n", run + 1,
                sim_time_s, wall.count(), factors.back(), simulation.firstJointPosition());
  }
  std::sort(factors.begin(), factors.end());
  const double median = factors.size() % 2 == 1
                            ? factors[factors.size() / 2]
                            : 0.5 * (factors[factors.size() / 2 - 1] + factors[factors.size() / 2]);
  std::printf("seed in-process headless real-time factor: median %.1f (min %.1f, max %.1f) over %d runs of %.1f s\n",
              median, factors.front(), factors.back(), repetitions, duration_s);
  return 0;
}
