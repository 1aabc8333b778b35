// The shared world's loop against the raw engine stepping the same world:
// 1, 4 and 16 seed arms (each under its position controller, commanded to
// 1 rad) beside 16 free boxes resting on the ground, 1 ms steps, on bullet
// and (with the argument `mujoco`) on mujoco.
//
//   raw bullet:  RawBulletWorld (world_fixture.hpp): one BulletScene with
//                every arm and box, each arm's position law written out
//   raw mujoco:  one MujocoWorld with every arm and box (servoloop's MuJoCo
//                engine used directly, as servoloop_bench_loop_vs_mujoco's
//                raw side: no SimRobotHW, transmissions, limits or
//                controllers); per step the same law's efforts, then one
//                mj_step of the world
//   shared:      a node (node::Node as `servoloop launch` builds it) of the
//                same robots in one world (world.shared: true), started
//                paused and stepped by stepWorld() as the Python package's
//                World.step() steps it: every robot's cycle (read,
//                controllers, write) and the world's step, its topics
//                delivered
//   separate:    the same node with world.shared: false (each robot in a
//                physics world of its own; nothing touches)
//
// The three are built side by side and stepped in turns, kChunkSteps steps
// each (raw, shared, separate, then the reverse order), for kRoundSteps steps;
// each is timed per turn. Turns a fraction of a second apart see the same
// speed of the machine, which moves on a shared VM, and the three worlds are
// in the same state at each turn (the same steps from the same start), so a
// round's ratio of summed times compares equal work. Each figure is the
// median of kRounds rounds (new worlds each) with the lowest and highest
// round. Two ratios: of wall time, and of CPU time (user + system of every
// thread of the process: the node steps its world on a thread of its own and
// delivers topics on others). Building the worlds is not counted.
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
constexpr std::uint64_t kSteps = 5000;  // the whole-process mode's run (--raw)
constexpr std::uint64_t kRoundSteps = 5000;
constexpr std::uint64_t kChunkSteps = 250;
constexpr int kRounds = 3;

// A world stepped by hand: the raw engine's or a node's.
class SteppedWorld {
 public:
  virtual ~SteppedWorld() = default;
  virtual void step(std::uint64_t steps) = 0;
};

// A raw world, whose first arm shows that its law drove it (the seed's gains
// take about 20 s to settle; in 5 s the arm is well on its way).
class RawWorld : public SteppedWorld {
 public:
  virtual double firstArmPosition() const = 0;
};

class RawBullet final : public RawWorld {
 public:
  RawBullet(const WorldFiles& files, int arms) : world_(files, arms) {}
  void step(std::uint64_t steps) override { world_.step(steps); }
  double firstArmPosition() const override { return world_.firstArmPosition(); }

 private:
  RawBulletWorld world_;
};

// A node of the world's launch file, paused, stepped by stepWorld().
class SteppedNode final : public SteppedWorld {
 public:
  SteppedNode(const WorldFiles& files, const std::string& backend, int arms, bool shared) {
    node::NodeOptions options;
    options.serve_ipc = false;
    options.real_time_factor = 0.0;
    options.start_paused = true;
    node_ = std::make_unique<node::Node>(node::parseLaunchFile(worldLaunchText(backend, arms, shared), "bench", files.dir),
                                         options);
    node_->start();
  }
  ~SteppedNode() override { node_->shutdown(); }
  void step(std::uint64_t steps) override {
    if (node_->stepWorld(steps) != steps) std::fprintf(stderr, "the node ran fewer steps than asked\n");
  }

 private:
  std::unique_ptr<node::Node> node_;
};

RunTimes timeSteps(SteppedWorld& world, std::uint64_t steps) {
  const RunTimer timer;
  world.step(steps);
  return timer.elapsed();
}

// "median [lowest–highest]" of per-repetition ratios.
std::string ratioText(std::vector<double> ratios) {
  std::sort(ratios.begin(), ratios.end());
  char text[64];
  std::snprintf(text, sizeof text, "%.3f [%.3f-%.3f]", median(ratios), ratios.front(), ratios.back());
  return text;
}

#ifdef SERVOLOOP_BENCH_MUJOCO
// The same world in one MujocoWorld, stepped by hand.
class RawMujoco final : public RawWorld {
 public:
  RawMujoco(const WorldFiles& files, int arms) {
    const auto arm_model = loadRobotModelFile((files.dir / "arm.urdf").string());
    const auto box_model = parseRobotModel(kBoxUrdf, "box");
    world_.init({kTimeStepS, {0.0, 0.0, -9.81}, true});
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
      bodies_.push_back(std::make_unique<sim_mujoco::MujocoPhysics>());
      bodies_.back()->joinWorld(world_);
      bodies_.back()->init(arm ? *arm_model : *box_model, settings, joints, arm ? "arm" : "box");
      if (arm) {
        HandWrittenPositionLaw law = HandWrittenPositionLaw::forJoint(seed, params, 0, *arm_model);
        law.setpoint_rad = 1.0;
        arms_.push_back({bodies_.back().get(), law});
      }
    }
    world_.restart();
  }
  ~RawMujoco() override {
    for (auto& body : bodies_) world_.remove(*body);
  }
  double firstArmPosition() const override { return arms_.front().physics->jointPosition(0); }
  void step(std::uint64_t steps) override {
    for (std::uint64_t n = 0; n < steps; ++n) {
      for (Arm& arm : arms_) {
        arm.physics->setJointEffort(0, arm.law.effort(arm.physics->jointPosition(0), arm.physics->jointVelocity(0)));
        arm.physics->step();
      }
      world_.step();
    }
  }

 private:
  struct Arm {
    sim_mujoco::MujocoPhysics* physics;
    HandWrittenPositionLaw law;
  };
  sim_mujoco::MujocoWorld world_;
  std::vector<std::unique_ptr<sim_mujoco::MujocoPhysics>> bodies_;
  std::vector<Arm> arms_;
};
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
    if (engine == "mujoco") {
      RawMujoco(files, arms).step(kSteps);
      return 0;
    }
#endif
    if (engine == "bullet") return runRawBulletWorld(files, arms, kSteps).wall_s > 0.0 ? 0 : 1;
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
  std::printf("=== The shared world: 16 boxes beside N seed arms, 1 ms steps; %d rounds of %llu steps in turns of "
              "%llu; median of the rounds [lowest-highest] ===\n",
              kRounds, static_cast<unsigned long long>(kRoundSteps), static_cast<unsigned long long>(kChunkSteps));
  std::printf("%-7s %-5s %9s %11s %26s %26s %26s\n", "engine", "arms", "raw (ms)", "shared (ms)", "shared/raw, wall",
              "shared/raw, CPU", "separate/shared, wall");
  for (const std::string& backend : backends) {
    for (const int arms : {1, 4, 16}) {
      const WorldFiles files(arms);
      std::vector<double> raw_ms, shared_ms, wall_ratio, cpu_ratio, separate_ratio;
      for (int round = 0; round < kRounds; ++round) {
        std::unique_ptr<RawWorld> raw;
#ifdef SERVOLOOP_BENCH_MUJOCO
        if (backend == "mujoco") raw = std::make_unique<RawMujoco>(files, arms);
#endif
        if (!raw) raw = std::make_unique<RawBullet>(files, arms);
        SteppedNode shared(files, backend, arms, true);
        SteppedNode separate(files, backend, arms, false);
        SteppedWorld* const worlds[3] = {raw.get(), &shared, &separate};
        RunTimes sums[3];
        for (std::uint64_t turn = 0; turn * kChunkSteps < kRoundSteps; ++turn) {
          for (int i = 0; i < 3; ++i) {
            const int which = turn % 2 == 0 ? i : 2 - i;
            const RunTimes times = timeSteps(*worlds[which], kChunkSteps);
            sums[which].wall_s += times.wall_s;
            sums[which].cpu_s += times.cpu_s;
          }
        }
        raw_ms.push_back(sums[0].wall_s * 1e3);
        shared_ms.push_back(sums[1].wall_s * 1e3);
        wall_ratio.push_back(sums[1].wall_s / sums[0].wall_s);
        cpu_ratio.push_back(sums[1].cpu_s / sums[0].cpu_s);
        separate_ratio.push_back(sums[2].wall_s / sums[1].wall_s);
        if (!(raw->firstArmPosition() > 0.5)) {
          std::fprintf(stderr, "raw %s: the first arm did not swing towards its setpoint\n", backend.c_str());
        }
      }
      std::printf("%-7s %-5d %9.1f %11.1f %26s %26s %26s\n", backend.c_str(), arms, median(raw_ms), median(shared_ms),
                  ratioText(wall_ratio).c_str(), ratioText(cpu_ratio).c_str(), ratioText(separate_ratio).c_str());
      std::fflush(stdout);
    }
  }
  return 0;
}
