#include "servoloop/world/world_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "servoloop/controller_manager/loop_clock.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::world {
namespace {

namespace loop_clock = controller_manager::loop_clock;

// How long an idle world (no member cycling) sleeps before asking its
// members again, unless a request wakes it first.
constexpr auto kIdlePoll = std::chrono::milliseconds(10);

bool contains(const std::vector<WorldMember*>& members, const WorldMember* member) {
  return std::find(members.begin(), members.end(), member) != members.end();
}

}  // namespace

WorldLoop::WorldLoop(hardware_interface::SimulatedWorld& world, WorldLoopOptions options)
    : world_(world), options_(std::move(options)) {
  const double rtf = options_.real_time_factor;
  if (!std::isfinite(rtf) || rtf < 0.0) {
    throw ConfigError(
        fmt::format("world loop: real_time_factor {} must be >= 0 (0 runs as fast as possible, 1 in real time)", rtf));
  }
  if (rtf > 0.0) wall_per_step_ns_ = world_.settings().time_step_s / rtf * 1e9;
  loop_clock::prepareCycleClock();  // calibrated here, not on the world's thread
}

WorldLoop::~WorldLoop() { stop(); }

void WorldLoop::start() {
  std::unique_lock lock(mutex_);
  if (started_) return;
  started_ = true;
  const std::vector<WorldMember*> first = joining_;
  thread_ = std::thread([this] { run(); });
  // The members added before all enter before the first cycle.
  wake_.wait(lock, [&] {
    return stop_requested_ || std::all_of(first.begin(), first.end(), [&](const WorldMember* member) {
             return contains(entered_, member) || !contains(joining_, member);
           });
  });
}

void WorldLoop::stop() {
  {
    std::lock_guard lock(mutex_);
    if (!thread_.joinable()) return;
    stop_requested_ = true;
    interrupt_.store(true, std::memory_order_release);
  }
  wake_.notify_all();
  thread_.join();
}

void WorldLoop::add(WorldMember& member) {
  std::unique_lock lock(mutex_);
  if (contains(entered_, &member) || contains(joining_, &member)) return;
  joining_.push_back(&member);
  if (!started_) return;  // enters when the loop starts
  interrupt_.store(true, std::memory_order_release);
  wake_.notify_all();
  wake_.wait(lock, [&] { return contains(entered_, &member) || stop_requested_; });
}

void WorldLoop::remove(WorldMember& member) {
  std::unique_lock lock(mutex_);
  if (const auto waiting = std::find(joining_.begin(), joining_.end(), &member); waiting != joining_.end()) {
    joining_.erase(waiting);
    wake_.notify_all();
    return;
  }
  // One entering now is waited for, then taken out like any other.
  wake_.wait(lock, [&] { return entering_ != &member; });
  if (!contains(entered_, &member)) return;
  if (!contains(leaving_, &member)) leaving_.push_back(&member);
  interrupt_.store(true, std::memory_order_release);
  wake_.notify_all();
  wake_.wait(lock, [&] { return !contains(entered_, &member); });
}

void WorldLoop::whilePaused(const std::function<void()>& change) {
  std::unique_lock lock(mutex_);
  if (stop_requested_) wake_.wait(lock, [&] { return !started_ || thread_exited_; });
  if (!started_ || thread_exited_) {
    // No thread steps the world (yet, or any more); the lock keeps a start out meanwhile.
    change();
    return;
  }
  // One pause at a time.
  wake_.wait(lock, [&] { return !pause_requested_ || thread_exited_; });
  pause_requested_ = true;
  interrupt_.store(true, std::memory_order_release);
  wake_.notify_all();
  wake_.wait(lock, [&] { return paused_ || thread_exited_; });
  const auto resume = [&] {
    pause_requested_ = false;
    wake_.notify_all();
  };
  lock.unlock();
  try {
    change();
  } catch (...) {
    lock.lock();
    resume();
    throw;
  }
  lock.lock();
  resume();
}

void WorldLoop::pause() {
  std::unique_lock lock(mutex_);
  const bool was_paused = physics_paused_;
  physics_paused_ = true;
  // Steps asked for meanwhile end here too.
  const bool stepping = step_budget_ > 0;
  step_budget_ = 0;
  if (was_paused && !stepping) return;
  standing_ = false;
  if (!started_ || thread_exited_) return;
  interrupt_.store(true, std::memory_order_release);
  wake_.notify_all();
  wake_.wait(lock, [&] { return standing_ || stop_requested_ || thread_exited_; });
}

void WorldLoop::unpause() {
  {
    std::lock_guard lock(mutex_);
    physics_paused_ = false;
    step_budget_ = 0;
  }
  wake_.notify_all();
}

bool WorldLoop::paused() const {
  std::lock_guard lock(mutex_);
  return physics_paused_;
}

std::uint64_t WorldLoop::stepPaused(std::uint64_t cycles) {
  std::unique_lock lock(mutex_);
  if (!physics_paused_) throw Error("the world is running; pause it first to step it");
  if (!started_ || thread_exited_ || stop_requested_ || steps_cancelled_) {
    throw Error("the world is not running; nothing can step it");
  }
  const std::uint64_t before = steps_stepped_;
  const std::uint64_t target = before + cycles;
  step_budget_ += cycles;
  wake_.notify_all();
  wake_.wait(lock, [&] {
    return steps_stepped_ >= target || step_budget_ == 0 || !physics_paused_ || stop_requested_ || thread_exited_ ||
           steps_cancelled_;
  });
  return std::min(cycles, steps_stepped_ - before);
}

void WorldLoop::cancelSteps() {
  {
    std::lock_guard lock(mutex_);
    steps_cancelled_ = true;
    step_budget_ = 0;
  }
  wake_.notify_all();
}

void WorldLoop::wake() {
  {
    std::lock_guard lock(mutex_);
    woken_ = true;
    interrupt_.store(true, std::memory_order_release);
  }
  wake_.notify_all();
}

bool WorldLoop::requestsWaiting() const {
  return !joining_.empty() || !leaving_.empty() || pause_requested_ || stop_requested_ || woken_ ||
         (standing_ && (!physics_paused_ || step_budget_ > 0)) || (physics_paused_ && !standing_);
}

void WorldLoop::serveRequests(std::unique_lock<std::mutex>& lock) {
  for (;;) {
    if (!leaving_.empty()) {
      WorldMember* member = leaving_.front();
      leaving_.erase(leaving_.begin());
      lock.unlock();
      member->leaveWorld();
      std::erase(members_, member);
      lock.lock();
      std::erase(entered_, member);
      wake_.notify_all();
      continue;
    }
    if (!joining_.empty() && !stop_requested_) {
      WorldMember* member = joining_.front();
      joining_.erase(joining_.begin());
      entering_ = member;
      lock.unlock();
      try {
        member->enterWorld();
      } catch (const std::exception& e) {
        logger().error("world loop: a robot failed to enter the world: {}", e.what());
      }
      members_.push_back(member);
      lock.lock();
      entered_.push_back(member);
      entering_ = nullptr;
      wake_.notify_all();
      continue;
    }
    if (pause_requested_ && !stop_requested_) {
      paused_ = true;
      wake_.notify_all();
      wake_.wait(lock, [&] { return !pause_requested_ || stop_requested_; });
      paused_ = false;
      continue;
    }
    return;
  }
}

void WorldLoop::run() {
  if (options_.on_thread_start) {
    try {
      options_.on_thread_start();
    } catch (const std::exception& e) {
      logger().error("world loop: preparing the world's thread failed: {}", e.what());
    }
  }
  std::unique_lock lock(mutex_);
  for (;;) {
    // A request from here on ends the coming segment early.
    interrupt_.store(false, std::memory_order_relaxed);
    woken_ = false;
    serveRequests(lock);
    if (stop_requested_) break;
    // Paused with no step asked for: the members do their work between
    // segments, and no cycle runs.
    const bool hold = physics_paused_ && step_budget_ == 0;
    const std::uint64_t budget = physics_paused_ ? step_budget_ : std::numeric_limits<std::uint64_t>::max();
    if (hold != standing_) {
      standing_ = hold;
      wake_.notify_all();
    }
    lock.unlock();

    std::uint64_t segment = budget;
    active_.clear();
    for (WorldMember* member : members_) {
      const std::uint64_t cycles = member->betweenSegments();
      if (cycles == 0) continue;
      active_.push_back(member);
      segment = std::min(segment, cycles);
    }
    if (active_.empty() || hold) {
      lock.lock();
      if (active_.empty() && step_budget_ > 0) {
        step_budget_ = 0;  // nobody cycles: the steps asked for cannot be run
        wake_.notify_all();
      }
      if (!standing_ && physics_paused_) {
        standing_ = true;
        wake_.notify_all();
      }
      wake_.wait_for(lock, kIdlePoll, [&] { return requestsWaiting(); });
      continue;
    }
    for (WorldObserver* observer : observers_) {
      segment = std::min(segment, std::max<std::uint64_t>(1, observer->betweenSegments(steps())));
    }
    for (WorldMember* member : active_) member->simulationLoop().beginExternalRun();
    if (options_.before_segment) options_.before_segment();
    const std::uint64_t ran = runSegment(segment);
    if (options_.after_segment) options_.after_segment();
    for (WorldMember* member : active_) member->simulationLoop().endExternalRun();
    lock.lock();
    if (physics_paused_ && step_budget_ > 0) {
      const std::uint64_t counted = std::min(ran, step_budget_);
      step_budget_ -= counted;
      steps_stepped_ += counted;
      // Waiters wake when all the steps asked for ran (calls from several
      // threads share one budget).
      if (step_budget_ == 0) wake_.notify_all();
    }
  }
  // Stopping: every member leaves, in the order they came.
  lock.unlock();
  for (WorldMember* member : members_) member->leaveWorld();
  members_.clear();
  lock.lock();
  entered_.clear();
  joining_.clear();
  leaving_.clear();
  thread_exited_ = true;
  standing_ = false;
  wake_.notify_all();
}

std::uint64_t WorldLoop::runSegment(std::uint64_t cycles) {
  const bool paced = wall_per_step_ns_ > 0.0;
  const auto max_lag_ns = static_cast<std::int64_t>(wall_per_step_ns_ * options_.max_catch_up_steps);
  std::int64_t anchor_ns = paced ? loop_clock::nowNs() : 0;
  std::uint64_t anchor_cycle = 0;
  std::uint64_t n = 0;
  for (; n < cycles; ++n) {
    if (interrupt_.load(std::memory_order_acquire)) break;
    for (WorldMember* member : active_) {
      controller_manager::SimulationLoop& loop = member->simulationLoop();
      if (loop.hardwareAskedToStop()) continue;
      loop.externalCycle();
      // Its hardware stopped it: the segment ends, so that the member sees
      // its fault (and a recovery) between segments.
      if (loop.hardwareAskedToStop()) interrupt_.store(true, std::memory_order_relaxed);
    }
    world_.step();
    // Only this thread writes it: no read-modify-write needed.
    steps_.store(steps_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
    if (!paced) continue;
    const std::int64_t end_ns = loop_clock::nowNs();
    const std::int64_t deadline_ns =
        anchor_ns + std::llround(static_cast<double>(n - anchor_cycle + 1) * wall_per_step_ns_);
    if (end_ns <= deadline_ns) {
      loop_clock::sleepUntilNs(deadline_ns);
    } else if (end_ns - deadline_ns > max_lag_ns) {
      // Too far behind to catch up: forget the backlog, restart from now.
      anchor_ns = end_ns;
      anchor_cycle = n + 1;
    }
  }
  return n;
}

}  // namespace servoloop::world
