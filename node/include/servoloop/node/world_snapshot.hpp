#pragma once
// What a viewer of the world needs each frame: every model's base pose and
// joint positions, the simulated time and the step count, copied on the
// world's thread between two segments of cycles (world/world_loop.hpp's
// WorldObserver), never inside a control cycle. Taken only once someone has
// asked for a frame (a browser view attached), at a fixed rate of world
// time; the copy allocates nothing (buffers sized when the models change),
// and the world's thread never waits for a reader: when a reader holds the
// snapshot, that snapshot is skipped.
#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "servoloop/hardware_interface/simulated_robot_hw.hpp"
#include "servoloop/world/world_loop.hpp"

namespace servoloop::node {

class WorldSnapshot final : public world::WorldObserver {
 public:
  static constexpr double kDefaultRateHz = 60.0;

  struct Model {
    std::string ns;
    // A floating base, read at each snapshot; nullptr for a fixed one.
    const hardware_interface::SimulatedRobotHW* floating = nullptr;
    double fixed_pose[7] = {0, 0, 0, 0, 0, 0, 1};  // x y z qx qy qz qw
    std::vector<std::string> joint_names;
    // The joint state interface's positions, in joint_names' order (read
    // between segments, when no cycle writes them).
    std::vector<const double*> joint_positions;
  };

  struct ModelFrame {
    std::string ns;
    double pose[7] = {0, 0, 0, 0, 0, 0, 1};  // x y z qx qy qz qw, world frame
    std::vector<std::string> joint_names;
    std::vector<double> joint_positions;
  };

  struct Frame {
    std::uint64_t generation = 0;  // changes with every setModels()
    std::uint64_t steps = 0;       // physics steps at the snapshot
    double sim_time_s = 0.0;
    std::vector<ModelFrame> models;
  };

  // `time_step_s`: the world's physics step. Throws servoloop::ConfigError
  // for a rate or step that is not > 0.
  explicit WorldSnapshot(double time_step_s, double rate_hz = kDefaultRateHz);

  // Non-real-time, with the world standing (WorldLoop::whilePaused) or not
  // yet started: the models to copy. The pointers must stay valid until
  // replaced. Takes a snapshot at once when enabled.
  void setModels(std::vector<Model> models, std::uint64_t steps);

  // Any thread: snapshots are taken from now on (idempotent).
  void enable() noexcept { enabled_.store(true, std::memory_order_relaxed); }
  bool enabled() const noexcept { return enabled_.load(std::memory_order_relaxed); }

  // World thread, between segments: copies when enabled and due.
  std::uint64_t betweenSegments(std::uint64_t steps) override;

  // Copies the state now: from the world's thread between segments, or
  // inside WorldLoop::whilePaused (a paused or reset world).
  void take(std::uint64_t steps) noexcept;

  // Any thread: the latest snapshot (waits only for another reader or for
  // the microseconds of a copy).
  void read(Frame& out) const;

 private:
  double time_step_s_;
  std::uint64_t steps_per_snapshot_ = 1;
  std::uint64_t next_step_ = 0;
  std::uint64_t last_steps_ = 0;
  std::atomic<bool> enabled_{false};
  std::vector<Model> models_;  // the world's thread (and whilePaused)
  mutable std::mutex frame_mutex_;  // the writer only tries it
  Frame frame_;
};

}  // namespace servoloop::node
