#pragma once
// What a control loop measured about itself: cycles, simulated and wall time,
// the achieved real-time factor, the per-cycle compute cost and deadline
// overruns.
//
// Threads. The loop's real-time thread is the only writer (the record*/set*
// calls: lock-free, allocation-free). Any thread may call snapshot() at any
// time: every field is an atomic, so each value read is one the writer stored.
// A paced loop (the wall clock; a simulation at a real-time factor, or driven
// one cycle at a time by SimulationLoop::cycleOnce) groups a
// cycle's records between beginUpdate() and endUpdate() (a sequence lock: the
// writer never waits); a snapshot that overlaps an open group reads again, so
// its figures all come from between two cycles — the wake-up latency count is
// the cycle count. A free-running simulation loop records without groups (a
// reader would hardly ever fit between two): its figures are read as they are,
// fields up to SimulationLoop::kFreeRunningTimingStride cycles apart (it
// counts untimed cycles, and publishes its elapsed times with its timed ones).
//
// Not every cycle need be timed: a free-running simulation loop times one
// cycle in kFreeRunningTimingStride and only counts the others
// (recordUntimedCycle). The compute and phase figures are then those of the
// timed cycles, and timed_cycles says how many there were. Each kind of
// duration is a DurationStatistics (duration_statistics.hpp): percentiles
// from a histogram preallocated inside the object, so recording never
// allocates.
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>

#include "servoloop/controller_manager/duration_statistics.hpp"

namespace servoloop::controller_manager {

struct LoopStatisticsSnapshot {
  std::uint64_t cycles = 0;           // loop cycles (physics steps in simulation)
  std::uint64_t control_updates = 0;  // ControllerManager::update calls
  double sim_time_s = 0.0;            // control time the loop advanced
  double wall_time_s = 0.0;           // wall time spent running, pacing sleeps included
  double real_time_factor = 0.0;      // sim_time_s / wall_time_s; 0 before any wall time passed

  // Per-cycle compute cost of the timed cycles: wall time of the cycle's
  // work (read, update, write, step; in a paced loop also the loop's
  // bookkeeping since the previous cycle), sleeps excluded. All 0 before the
  // first timed cycle.
  std::uint64_t timed_cycles = 0;  // cycles the figures below come from
  double compute_min_s = 0.0;
  double compute_mean_s = 0.0;
  double compute_max_s = 0.0;
  double compute_p50_s = 0.0;  // from the histogram
  double compute_p99_s = 0.0;  // from the histogram

  std::uint64_t overruns = 0;         // cycles that ended after their deadline
  // Deadlines no cycle started at (the wall clock skips those an overrun or
  // a pause missed, and those of a stop): cycles + skipped_deadlines are the
  // deadlines the grid had.
  std::uint64_t skipped_deadlines = 0;
  std::uint64_t schedule_resets = 0;  // times a loop gave up catching up on a backlog
  std::uint64_t hardware_errors = 0;  // read/write/step calls that returned ReturnType::error

  // Phases of the timed cycles: the hardware's read() and write() calls.
  DurationSnapshot read;
  DurationSnapshot write;
  // Wall-clock loops only (count 0 otherwise): how late each cycle started
  // after its deadline (wake-up latency, what cyclictest measures), and how
  // far each period between two cycle starts was from the nominal one
  // (|measured − nominal|, period jitter).
  DurationSnapshot wakeup_latency;
  DurationSnapshot period_jitter;
};

class LoopStatistics {
 public:
  // The histogram layout (DurationStatistics'), kept here for the tests.
  static constexpr std::int64_t kLinearBuckets = DurationStatistics::kLinearBuckets;
  static constexpr std::size_t kBucketCount = DurationStatistics::kBucketCount;

  LoopStatistics() { reset(); }
  LoopStatistics(const LoopStatistics&) = delete;
  LoopStatistics& operator=(const LoopStatistics&) = delete;

  // --- Writer side (real-time thread only) ---

  // Open and close a group of records snapshot() shows whole or not at all
  // (one cycle's). Groups do not nest; every beginUpdate has its endUpdate.
  // No fence: every record is a release store and every read an acquire load,
  // so a reader that reads any record of an open group then reads the
  // sequence changed (and ThreadSanitizer, which has no model of standalone
  // fences, sees every ordering it relies on).
  void beginUpdate() noexcept {
    update_sequence_.store(update_sequence_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
  }
  void endUpdate() noexcept {
    update_sequence_.store(update_sequence_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
  }

  // One finished cycle that took compute_ns of work; control_update: the
  // manager was updated in it.
  void recordCycle(std::int64_t compute_ns, bool control_update) noexcept;
  // One finished cycle that was not timed: counted, without a compute cost.
  void recordUntimedCycle(bool control_update) noexcept {
    if (control_update) bump(control_updates_);
    cycles_.store(cycles_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
  }
  // The loop's cumulative simulated (control) and wall time.
  void setElapsed(double sim_time_s, std::int64_t wall_time_ns) noexcept;
  // An overrun; `skipped` deadlines get no cycle because of it.
  void recordOverrun(std::uint64_t skipped = 0) noexcept {
    bump(overruns_);
    recordSkippedDeadlines(skipped);
  }
  // Deadlines no cycle started at without an overrun (a stopped loop's).
  void recordSkippedDeadlines(std::uint64_t skipped) noexcept {
    skipped_deadlines_.store(skipped_deadlines_.load(std::memory_order_relaxed) + skipped, std::memory_order_release);
  }
  // Phase and timing figures of the current (timed) cycle.
  void recordRead(std::int64_t ns) noexcept { read_.record(ns); }
  void recordWrite(std::int64_t ns) noexcept { write_.record(ns); }
  void recordWakeupLatency(std::int64_t ns) noexcept { wakeup_latency_.record(ns); }
  void recordPeriodJitter(std::int64_t ns) noexcept { period_jitter_.record(ns); }
  // At the start of a cycle: carries out a reset another thread asked for
  // (requestReset): counts and figures back to zero, control and wall time
  // kept. True if it did.
  bool applyRequestedReset() noexcept {
    if (!reset_requested_.load(std::memory_order_acquire)) return false;
    // Control and wall time run on: they are the loop's clock, not a figure.
    const double sim_time_s = sim_time_s_.load(std::memory_order_relaxed);
    const std::int64_t wall_time_ns = wall_time_ns_.load(std::memory_order_relaxed);
    reset();
    setElapsed(sim_time_s, wall_time_ns);
    reset_requested_.store(false, std::memory_order_release);
    return true;
  }
  void recordScheduleReset() noexcept { bump(schedule_resets_); }
  void recordHardwareError() noexcept { bump(hardware_errors_); }

  // Back to zero. Only on the writer's thread, or while no loop thread records.
  void reset() noexcept;
  // Any thread: the writer resets at the start of its next cycle
  // (applyRequestedReset); resetPending() is true until then.
  void requestReset() noexcept { reset_requested_.store(true, std::memory_order_release); }
  bool resetPending() const noexcept { return reset_requested_.load(std::memory_order_acquire); }

  // --- Reader side (any thread) ---

  // How long snapshot() waits, by default, for a group the writer has open
  // (a cycle takes microseconds; a hardware read that hangs must not hang the
  // reader): after it, the figures are read as they are, a cycle apart.
  static constexpr std::chrono::milliseconds kSnapshotMaxWait{50};

  // Not for the real-time thread (it may yield while the writer's group is open).
  LoopStatisticsSnapshot snapshot(std::chrono::nanoseconds max_wait = kSnapshotMaxWait) const noexcept;
  // Two figures alone, without reading the histograms: cycles so far, and
  // the control time the loop advanced.
  std::uint64_t cycles() const noexcept { return cycles_.load(std::memory_order_acquire); }
  double simTime() const noexcept { return sim_time_s_.load(std::memory_order_acquire); }

  // Non-real-time. The end-of-run summary, e.g.
  //   "loop: 1000 cycles (1000 control updates), 1.000 s simulated in 1.002 s wall
  //    (real-time factor 0.998); compute per cycle min 3.1 us, mean 4.0 us, p50 3.9 us,
  //    p99 9.8 us, max 41.0 us; 0 overruns, 0 schedule resets, 0 hardware errors"
  // ("compute per cycle (63 of 1000 cycles timed) min ..." when not every
  // cycle was timed).
  std::string summary() const;
  static std::string summary(const LoopStatisticsSnapshot& stats);

  // DurationStatistics' bucket layout (for the tests).
  static std::size_t bucketIndex(std::int64_t value_ns) noexcept { return DurationStatistics::bucketIndex(value_ns); }
  static std::int64_t bucketLower(std::size_t index) noexcept { return DurationStatistics::bucketLower(index); }
  static std::int64_t bucketUpper(std::size_t index) noexcept { return DurationStatistics::bucketUpper(index); }

 private:
  // Single writer: a relaxed load and a store is an atomic increment here
  // (a release store, as every record: see beginUpdate).
  static void bump(std::atomic<std::uint64_t>& counter) noexcept {
    counter.store(counter.load(std::memory_order_relaxed) + 1, std::memory_order_release);
  }

  // Every field read at once, as it is now.
  LoopStatisticsSnapshot readFields() const noexcept;

  // Odd while the writer has a group open (beginUpdate/endUpdate).
  std::atomic<std::uint64_t> update_sequence_{0};
  std::atomic<std::uint64_t> cycles_{0};
  std::atomic<std::uint64_t> control_updates_{0};
  std::atomic<double> sim_time_s_{0.0};
  std::atomic<std::int64_t> wall_time_ns_{0};
  std::atomic<std::uint64_t> overruns_{0};
  std::atomic<std::uint64_t> skipped_deadlines_{0};
  std::atomic<std::uint64_t> schedule_resets_{0};
  std::atomic<std::uint64_t> hardware_errors_{0};
  DurationStatistics compute_;
  DurationStatistics read_;
  DurationStatistics write_;
  DurationStatistics wakeup_latency_;
  DurationStatistics period_jitter_;
  std::atomic<bool> reset_requested_{false};
};

}  // namespace servoloop::controller_manager
