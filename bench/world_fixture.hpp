#pragma once
// The shared world the world and view benchmarks run: N seed arms (each
// under its position controller, commanded to 1 rad) beside 16 free boxes
// resting on the ground, 1 ms steps; its files, its launch file, and the
// same world stepped by hand on raw Bullet (one BulletScene, each arm's
// position law written out: HandWrittenPositionLaw).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "bench_support.hpp"

namespace servoloop::bench {

inline constexpr int kWorldBoxes = 16;

// The box every benchmark world holds (a 1 kg, 0.2 m cube).
extern const char* const kBoxUrdf;

// Where the k-th box and arm stand.
double boxX(int k);
double boxY(int k);
double armX(int k);

// The folder with the seed arm (its gazebo_ros_control block, which names its
// namespace, left out), the box, and every arm's controllers.
struct WorldFiles {
  std::filesystem::path dir;
  bool keep = false;
  // In a temporary folder removed at the end, or in `folder`, kept.
  explicit WorldFiles(int arms, const std::filesystem::path& folder = {});
  ~WorldFiles();
  WorldFiles(const WorldFiles&) = delete;
  WorldFiles& operator=(const WorldFiles&) = delete;
};

// The launch file of that world (arms, boxes, the arms' commands at t = 0).
std::string worldLaunchText(const std::string& backend, int arms, bool shared);

// The same world stepped by hand on raw Bullet: one BulletScene with every
// arm and box; per step, each arm's position law written out
// (HandWrittenPositionLaw: the servoloop controller's law and limits), then
// one scene step.
class RawBulletWorld {
 public:
  RawBulletWorld(const WorldFiles& files, int arms);
  ~RawBulletWorld();
  RawBulletWorld(const RawBulletWorld&) = delete;
  RawBulletWorld& operator=(const RawBulletWorld&) = delete;

  void step(std::uint64_t steps);
  double firstArmPosition() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// Wall and CPU seconds of `steps` of a new RawBulletWorld (its building is
// not counted).
RunTimes runRawBulletWorld(const WorldFiles& files, int arms, std::uint64_t steps);

}  // namespace servoloop::bench
