#pragma once
// The loop of a simulated world: one thread, the world's real-time thread,
// runs every robot's control cycle and then steps the world's physics once,
// cycle after cycle, in lockstep with simulated time:
//
//   for each robot: read, controllers (when due at its own rate), write, step()
//   world.step()        -- one physics step for every robot and object
//
// so the controllers of one cycle all see the state of the same step, and a
// robot's commands reach the physics in the step right after its cycle.
//
// The loop runs in segments of cycles. Between two segments, with no cycle
// in progress, each member (WorldMember: a robot of the world) does its
// non-real-time work (timed publications, delivering its topics, recovering
// from a fault) and says how many cycles it may run before it needs that
// again; the next segment is the shortest of those. Members join and leave,
// and the world's bodies change (whilePaused), only between segments.
//
// A member whose hardware asked to stop (a fault) runs no cycle until it
// says so again; the others run on, and the world's physics goes on with
// them (its bodies keep their last commands' motors and get no efforts).
//
// Pause (Gazebo's pause_physics): no cycle runs and simulated time stands,
// while the members still do their between-segment work (topics delivered,
// requests served); stepPaused() then runs a given number of cycles. A
// reset happens inside whilePaused (the node's resetWorld), which may also
// set the step count back to 0 (rewindSteps).
//
// Pacing: free-running (real-time factor 0) runs cycles back to back; paced,
// the cycle ending simulated time t ends no earlier than the segment's start
// + (t - t_segment) / real_time_factor in wall time, with the catch-up rule
// of SimulationLoop (controller_manager/simulation_loop.hpp).
//
// Threading: the public methods are for any thread except the world's own
// (its members' callbacks must not call them). Cycles allocate nothing, take
// no lock and never log.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "servoloop/controller_manager/simulation_loop.hpp"
#include "servoloop/hardware_interface/simulated_world.hpp"

namespace servoloop::world {

// One robot (or object) of the world, as the world loop drives it. Every
// method is called on the world's thread.
class WorldMember {
 public:
  virtual ~WorldMember() = default;
  // Once, before the member's first cycle.
  virtual void enterWorld() = 0;
  // Between two segments: the member's non-real-time work due now. Returns
  // how many cycles it may run before it needs this call again; 0 when it
  // runs none now (finished, or standing in a fault); it is asked again at
  // the next segment boundary.
  virtual std::uint64_t betweenSegments() = 0;
  // Once, after its last cycle (removed, or the world stopped).
  virtual void leaveWorld() = 0;
  // Its loop, whose cycles the world runs (SimulationLoop::externalCycle).
  virtual controller_manager::SimulationLoop& simulationLoop() = 0;
};

// Watches the whole world between two segments of cycles (e.g. publishing
// every model's state at a fixed rate of world time). Called on the world's
// thread, never while it stands paused.
class WorldObserver {
 public:
  virtual ~WorldObserver() = default;
  // Between two segments that run cycles: `steps` physics steps have run.
  // Returns how many more steps may run before it needs this call again
  // (at least 1).
  virtual std::uint64_t betweenSegments(std::uint64_t steps) = 0;
};

struct WorldLoopOptions {
  // Simulated seconds per wall second; 0: free-running.
  double real_time_factor = 0.0;
  // How late (in physics steps of wall time) a paced loop may fall before it
  // restarts its schedule.
  std::uint32_t max_catch_up_steps = 10;
  // Called first on the world's thread (e.g. its scheduling and affinity).
  std::function<void()> on_thread_start;
  // Called on the world's thread right before and right after each segment
  // of cycles (the real-time part), e.g. to observe it. Must not throw.
  std::function<void()> before_segment;
  std::function<void()> after_segment;
};

class WorldLoop {
 public:
  // `world` must be initialised and outlive the loop. Throws
  // servoloop::ConfigError for a negative or non-finite real-time factor.
  WorldLoop(hardware_interface::SimulatedWorld& world, WorldLoopOptions options);
  // stop().
  ~WorldLoop();
  WorldLoop(const WorldLoop&) = delete;
  WorldLoop& operator=(const WorldLoop&) = delete;

  // Starts the world's thread. The members added before enter first, in the
  // order they were added, before the first cycle; returns once they have.
  void start();
  // Every member leaves (leaveWorld) and the thread ends. Idempotent.
  void stop();

  // Adds a member (it must stay alive until removed or the loop stopped).
  // Once the loop runs, returns after the member's enterWorld() has run on
  // the world's thread; before that, it enters when the loop starts.
  void add(WorldMember& member);
  // Removes a member; returns after its leaveWorld() has run (at once, with
  // no call, if it is not a member).
  void remove(WorldMember& member);
  // Runs `change` on the calling thread while the world's thread stands
  // between two segments (no cycle, no physics step): for adding bodies to
  // the world or taking them out. Exceptions from `change` propagate.
  void whilePaused(const std::function<void()>& change);
  // Adds an observer of the world (called in the order added); before
  // start(), or inside whilePaused's change. It must outlive the loop.
  void addObserver(WorldObserver& observer) { observers_.push_back(&observer); }
  // Ends the current segment early, so that every member's betweenSegments()
  // runs soon (e.g. after a request it serves there).
  void wake();

  // Pauses the world: no cycle runs until unpause() (or stepPaused());
  // returns once the segment in progress has ended, so the world's time
  // stands. Before start(), the world starts paused (its members still
  // enter). Idempotent.
  void pause();
  // Lets the world run again (any steps still asked for are dropped).
  void unpause();
  bool paused() const;
  // While paused: runs `cycles` more cycles (each active member's, then one
  // physics step) and returns how many ran once they have: fewer when no
  // member cycles (all finished or in a fault), when pause() or unpause()
  // comes meanwhile, or the loop stops. Calls from several threads add up.
  // Throws servoloop::Error when the world is not paused or not running.
  std::uint64_t stepPaused(std::uint64_t cycles);
  // Ends every stepPaused() waiting now and refuses later ones (a node
  // shutting down).
  void cancelSteps();

  // Physics steps of the world so far (any thread).
  std::uint64_t steps() const noexcept { return steps_.load(std::memory_order_acquire); }
  // Only inside whilePaused's change (or before start()): the step count
  // starts again from 0 (a reset world).
  void rewindSteps() noexcept { steps_.store(0, std::memory_order_release); }

 private:
  void run();
  // Returns how many cycles it ran (fewer when interrupted).
  std::uint64_t runSegment(std::uint64_t cycles);
  // Under mutex_: joins and leaves waiting, a pause, a stop.
  bool requestsWaiting() const;
  void serveRequests(std::unique_lock<std::mutex>& lock);

  hardware_interface::SimulatedWorld& world_;
  WorldLoopOptions options_;
  double wall_per_step_ns_ = 0.0;  // wall time of one step when paced

  std::thread thread_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  // Under mutex_.
  std::vector<WorldMember*> joining_;
  std::vector<WorldMember*> leaving_;
  std::vector<WorldMember*> entered_;  // members whose enterWorld() has run
  bool pause_requested_ = false;
  bool paused_ = false;
  bool stop_requested_ = false;
  bool started_ = false;
  bool thread_exited_ = false;  // run() has returned: nothing steps the world
  bool woken_ = false;
  bool physics_paused_ = false;   // pause() .. unpause()
  std::uint64_t step_budget_ = 0;  // cycles stepPaused() still asks for
  std::uint64_t steps_stepped_ = 0;  // cycles run for stepPaused() since the start
  bool steps_cancelled_ = false;
  bool standing_ = false;         // the thread holds the paused world (no segment runs)
  WorldMember* entering_ = nullptr;  // whose enterWorld() runs now

  // The world's thread only (and whilePaused's change).
  std::vector<WorldObserver*> observers_;
  std::vector<WorldMember*> members_;
  std::vector<WorldMember*> active_;  // members cycling in this segment

  std::atomic<bool> interrupt_{false};  // ends the current segment
  std::atomic<std::uint64_t> steps_{0};
};

}  // namespace servoloop::world
