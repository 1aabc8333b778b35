// LoopStatistics: single-writer counters and a fixed log-linear histogram.
#include "servoloop/controller_manager/loop_statistics.hpp"

#include <thread>

#include <fmt/format.h>

namespace servoloop::controller_manager {

void LoopStatistics::recordCycle(std::int64_t compute_ns, bool control_update) noexcept {
  compute_.record(compute_ns);
  // Then counted like any cycle, last (its release store): a reader that sees
  // this cycle counted sees its cost too.
  recordUntimedCycle(control_update);
}

void LoopStatistics::setElapsed(double sim_time_s, std::int64_t wall_time_ns) noexcept {
  sim_time_s_.store(sim_time_s, std::memory_order_release);
  wall_time_ns_.store(wall_time_ns, std::memory_order_release);
}

void LoopStatistics::reset() noexcept {
  cycles_.store(0, std::memory_order_release);
  control_updates_.store(0, std::memory_order_release);
  sim_time_s_.store(0.0, std::memory_order_release);
  wall_time_ns_.store(0, std::memory_order_release);
  overruns_.store(0, std::memory_order_release);
  skipped_deadlines_.store(0, std::memory_order_release);
  schedule_resets_.store(0, std::memory_order_release);
  hardware_errors_.store(0, std::memory_order_release);
  compute_.reset();
  read_.reset();
  write_.reset();
  wakeup_latency_.reset();
  period_jitter_.reset();
}

LoopStatisticsSnapshot LoopStatistics::snapshot(std::chrono::nanoseconds max_wait) const noexcept {
  const auto give_up = std::chrono::steady_clock::now() + max_wait;
  for (int attempt = 0;; ++attempt) {
    const std::uint64_t before = update_sequence_.load(std::memory_order_acquire);
    if (before % 2 == 0) {
      const LoopStatisticsSnapshot s = readFields();
      // readFields' acquire loads keep this load after them: a group the
      // writer opened meanwhile, and wrote any of them in, changed the sequence.
      if (update_sequence_.load(std::memory_order_relaxed) == before) return s;
    }
    if (std::chrono::steady_clock::now() >= give_up) return readFields();
    // A cycle takes microseconds: yield a few times, then stop spinning (a
    // hardware call that hangs keeps the group open).
    if (attempt < 8) {
      std::this_thread::yield();
    } else {
      std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
  }
}

LoopStatisticsSnapshot LoopStatistics::readFields() const noexcept {
  LoopStatisticsSnapshot s;
  s.cycles = cycles_.load(std::memory_order_acquire);
  s.control_updates = control_updates_.load(std::memory_order_acquire);
  s.sim_time_s = sim_time_s_.load(std::memory_order_acquire);
  s.wall_time_s = static_cast<double>(wall_time_ns_.load(std::memory_order_acquire)) * 1e-9;
  s.real_time_factor = s.wall_time_s > 0.0 ? s.sim_time_s / s.wall_time_s : 0.0;
  s.overruns = overruns_.load(std::memory_order_acquire);
  s.skipped_deadlines = skipped_deadlines_.load(std::memory_order_acquire);
  s.schedule_resets = schedule_resets_.load(std::memory_order_acquire);
  s.hardware_errors = hardware_errors_.load(std::memory_order_acquire);
  if (s.cycles == 0) return s;
  const DurationSnapshot compute = compute_.snapshot();
  s.timed_cycles = compute.count;
  s.compute_min_s = compute.min_s;
  s.compute_mean_s = compute.mean_s;
  s.compute_max_s = compute.max_s;
  s.compute_p50_s = compute.p50_s;
  s.compute_p99_s = compute.p99_s;
  s.read = read_.snapshot();
  s.write = write_.snapshot();
  s.wakeup_latency = wakeup_latency_.snapshot();
  s.period_jitter = period_jitter_.snapshot();
  return s;
}

std::string LoopStatistics::summary() const { return summary(snapshot()); }

std::string LoopStatistics::summary(const LoopStatisticsSnapshot& s) {
  const std::string timed =
      s.timed_cycles == s.cycles ? std::string() : fmt::format(" ({} of {} cycles timed)", s.timed_cycles, s.cycles);
  std::string text = fmt::format(
      "loop: {} cycles ({} control updates), {:.3f} s simulated in {:.3f} s wall (real-time factor {:.3f}); "
      "compute per cycle{} min {}, mean {}, p50 {}, p99 {}, max {}; "
      "{} overruns, {} schedule resets, {} hardware errors",
      s.cycles, s.control_updates, s.sim_time_s, s.wall_time_s, s.real_time_factor, timed,
      formatDuration(s.compute_min_s), formatDuration(s.compute_mean_s), formatDuration(s.compute_p50_s),
      formatDuration(s.compute_p99_s), formatDuration(s.compute_max_s), s.overruns, s.schedule_resets,
      s.hardware_errors);
  if (s.wakeup_latency.count > 0) {
    text += fmt::format("; wake-up latency {}; period jitter {}", toText(s.wakeup_latency), toText(s.period_jitter));
  }
  return text;
}

}  // namespace servoloop::controller_manager
