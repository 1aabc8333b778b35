// The shared world's loop against the raw engine stepping the same world:
// 1, 4 and 16 seed arms (each under its position controller, commanded to
// 1 rad) beside 16 free boxes resting on the ground, 5 s of 1 ms steps, on
// bullet and (with the argument `mujoco`) on mujoco.
//
//   raw bullet:  one BulletScene with every arm and box; per step, each arm's
//                position law written out by hand (HandWrittenPositionLaw,
//                the servoloop controller's law and limits) and one scene step
//   raw mujoco:  one MujocoWorld with every arm and box (servoloop's MuJoCo
//                engine used directly, as servoloop_bench_loop_vs_mujoco's
//                raw side: no SimRobotHW, transmissions, limits or
//                controllers); per step the same law's efforts, then one
//                mj_step of the world
//   servoloop:   a node (node::Node, as `servoloop launch` builds and runs it)
//                of the same robots, free-running: every robot's cycle
//                (read, controllers, write) and the world's step, its topics
//                delivered, in one world (world.shared: true)
//   separate:    the same node with world.shared: false (each robot in a
//                physics world of its own; nothing touches)
//
// Each repetition runs the three back to back (in turns of order: raw,
// shared, separate, then the reverse), and each figure is the median over 9
// repetitions of that repetition's own ratio, with the lowest and highest:
// a ratio of two runs seconds apart, so that the machine's speed, which moves
// on a shared VM, cancels. Two ratios: of wall time, and of CPU time (user +
// system of every thread of the process: the work done, which a busy
// neighbour stretches far less). The node's construction — URDFs, plugins —
// is not counted, as the raw world's building is not. The node runs its loop
// on one thread and delivers its topics on others (their CPU counted); the
// raw loop is one thread.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "loop_fixtures.hpp"
#include "world_fixture.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/node/launch_file.hpp"
#include "servoloop/node/node.hpp"
#ifdef SERVOLOOP_BENCH_MUJOCO
#include "servoloop/sim_mujoco/mujoco_physics.hpp"
#include "servoloop/sim_mujoco/mujoco_world.hpp"
#endif

namespace servoloop::bench {
namespace {

namespace fs = std::filesystem;
constexpr std::uint64_t kSteps = 5000;
constexpr int kRepetitions = 9;

// Wall and CPU seconds of kSteps of the node (built beforehand).
RunTimes runNode(const WorldFiles& files, const std::string& backend, int arms, bool shared) {
  return timesOfNodeRun(worldLaunchText(backend, arms, shared), files.dir, static_cast<double>(kSteps) * kTimeStepS);
}

RunTimes runRaw(const WorldFiles& files, int arms) { return runRawBulletWorld(files, arms, kSteps); }

// "median [lowest–highest]" of per-repetition ratios.
std::string ratioText(std::vector<double> ratios) {
  std::sort(ratios.begin(), ratios.end());
  char text[64];
  std::snprintf(text, sizeof text, "%.3f [%.3f-%.3f]", median(ratios), ratios.front(), ratios.back());
  return text;
}

#ifdef SERVOLOOP_BENCH_MUJOCO
// Wall and CPU seconds of kSteps of the same world in one MujocoWorld.
RunTimes runRawMujoco(const WorldFiles& files, int arms) {
  const auto arm_model = loadRobotModelFile((files.dir / "arm.urdf").string());
  const auto box_model = parseRobotModel(kBoxUrdf, "box");
  sim_mujoco::MujocoWorld world;
  world.init({kTimeStepS, {0.0, 0.0, -9.81}, true});
  std::vector<std::unique_ptr<sim_mujoco::MujocoPhysics>> bodies;
  struct Arm {
    sim_mujoco::MujocoPhysics* physics;
    HandWrittenPositionLaw law;
  };
  std::vector<Arm> laws;
  const RobotCase seed = seedRobot();
  const YAML::Node params = seed.namespaceParams();
  for (int k = 0; k < arms + kWorldBoxes; ++k) {
    const bool arm = k < arms;
    sim_common::SimSettings settings;
    settings.time_step_s = kTimeStepS;
    settings.ground_plane = true;
    settings.base = arm ? sim_common::BaseMode::fixed : sim_common::BaseMode::floating;
    settings.base_position = arm ? Eigen::Vector3d(armX(k), 0.0, 0.0)
                                 : Eigen::Vector3d(boxX(k - arms), boxY(k - arms), 0.1);
    std::vector<sim_common::EngineJointConfig> joints;
    if (arm) joints.push_back(sim_common::EngineJointConfig{"joint1"});
    bodies.push_back(std::make_unique<sim_mujoco::MujocoPhysics>());
    bodies.back()->joinWorld(world);
    bodies.back()->init(arm ? *arm_model : *box_model, settings, joints, arm ? "arm" : "box");
    if (arm) {
      HandWrittenPositionLaw law = HandWrittenPositionLaw::forJoint(seed, params, 0, *arm_model);
      law.setpoint_rad = 1.0;
      laws.push_back({bodies.back().get(), law});
    }
  }
  world.restart();
  const RunTimer timer;
  for (std::uint64_t n = 0; n < kSteps; ++n) {
    for (Arm& arm : laws) {
      arm.physics->setJointEffort(0, arm.law.effort(arm.physics->jointPosition(0), arm.physics->jointVelocity(0)));
      arm.physics->step();
    }
    world.step();
  }
  const RunTimes times = timer.elapsed();
  if (!(laws.front().physics->jointPosition(0) > 0.5)) {
    std::fprintf(stderr, "raw mujoco: the first arm did not swing towards its setpoint\n");
  }
  for (auto& body : bodies) world.remove(*body);
  bodies.clear();
  return times;
}
#endif

}  // namespace
}  // namespace servoloop::bench

// The whole-process comparison, each side a process of its own that loads
// its robots, builds its world and runs 5 s:
//   servoloop_bench_world --write DIR N ENGINE   writes DIR/world.launch.yaml
//       and its robots, for `servoloop launch DIR/world.launch.yaml --duration 5`
//   servoloop_bench_world --raw N ENGINE         the raw world of N arms, once
int wholeProcessMode(int argc, char** argv) {
  using namespace servoloop::bench;
  const std::string mode = argv[1];
  if (mode == "--write" && argc == 5) {
    const int arms = std::stoi(argv[3]);
    const WorldFiles files(arms, argv[2]);
    std::ofstream(files.dir / "world.launch.yaml") << worldLaunchText(argv[4], arms, true);
    return 0;
  }
  if (mode == "--raw" && argc == 4) {
    const int arms = std::stoi(argv[2]);
    const std::string engine = argv[3];
    const WorldFiles files(arms);
#ifdef SERVOLOOP_BENCH_MUJOCO
    if (engine == "mujoco") return runRawMujoco(files, arms).wall_s > 0.0 ? 0 : 1;
#endif
    if (engine == "bullet") return runRaw(files, arms).wall_s > 0.0 ? 0 : 1;
  }
  std::fprintf(stderr, "usage: servoloop_bench_world [mujoco] | --write DIR ARMS ENGINE | --raw ARMS ENGINE\n");
  return 2;
}

int main(int argc, char** argv) {
  using namespace servoloop::bench;
  if (argc > 1 && std::string(argv[1]).rfind("--", 0) == 0) return wholeProcessMode(argc, argv);
  std::vector<std::string> backends{"bullet"};
#ifdef SERVOLOOP_BENCH_MUJOCO
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "mujoco") backends.push_back("mujoco");
  }
#else
  (void)argc;
  (void)argv;
#endif
  std::printf("=== The shared world: %llu steps of 1 ms, 16 boxes beside N seed arms; medians of %d paired "
              "repetitions, [lowest-highest] ===\n",
              static_cast<unsigned long long>(kSteps), kRepetitions);
  std::printf("%-7s %-5s %9s %11s %26s %26s %18s\n", "engine", "arms", "raw (ms)", "shared (ms)",
              "shared/raw, wall", "shared/raw, CPU", "separate/shared");
  for (const std::string& backend : backends) {
    for (const int arms : {1, 4, 16}) {
      const WorldFiles files(arms);
      std::vector<double> raw_ms, shared_ms, wall_ratio, cpu_ratio, separate_ratio;
      for (int r = 0; r < kRepetitions; ++r) {
        const auto raw_run = [&] {
#ifdef SERVOLOOP_BENCH_MUJOCO
          return backend == "mujoco" ? runRawMujoco(files, arms) : runRaw(files, arms);
#else
          return runRaw(files, arms);
#endif
        };
        RunTimes raw, shared, separate;
        if (r % 2 == 0) {
          raw = raw_run();
          shared = runNode(files, backend, arms, true);
          separate = runNode(files, backend, arms, false);
        } else {
          separate = runNode(files, backend, arms, false);
          shared = runNode(files, backend, arms, true);
          raw = raw_run();
        }
        raw_ms.push_back(raw.wall_s * 1e3);
        shared_ms.push_back(shared.wall_s * 1e3);
        wall_ratio.push_back(shared.wall_s / raw.wall_s);
        cpu_ratio.push_back(shared.cpu_s / raw.cpu_s);
        separate_ratio.push_back(separate.wall_s / shared.wall_s);
      }
      std::printf("%-7s %-5d %9.1f %11.1f %26s %26s %18s\n", backend.c_str(), arms, median(raw_ms), median(shared_ms),
                  ratioText(wall_ratio).c_str(), ratioText(cpu_ratio).c_str(), ratioText(separate_ratio).c_str());
      std::fflush(stdout);
    }
  }
  return 0;
}
