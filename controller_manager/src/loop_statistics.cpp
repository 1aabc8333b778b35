// LoopStatistics: single-writer counters and a fixed log-linear histogram.
#include "servoloop/controller_manager/loop_statistics.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include <spdlog/fmt/fmt.h>

namespace servoloop::controller_manager {

namespace {
constexpr double kSecondsPerNs = 1e-9;
constexpr std::int64_t kUnsetMin = std::numeric_limits<std::int64_t>::max();

// "3.1 us", "12.4 ms", ... for the summary.
std::string formatDuration(double seconds) {
  const double magnitude = std::abs(seconds);
  if (magnitude >= 1.0) return fmt::format("{:.3f} s", seconds);
  if (magnitude >= 1e-3) return fmt::format("{:.3f} ms", seconds * 1e3);
  if (magnitude >= 1e-6) return fmt::format("{:.1f} us", seconds * 1e6);
  return fmt::format("{:.0f} ns", seconds * 1e9);
}
}  // namespace

std::size_t LoopStatistics::bucketIndex(std::int64_t value_ns) noexcept {
  if (value_ns < kLinearBuckets) return static_cast<std::size_t>(std::max<std::int64_t>(value_ns, 0));
  const auto value = static_cast<std::uint64_t>(value_ns);
  const int exponent = std::bit_width(value) - 1;  // floor(log2(value)) >= kSubBucketBits
  if (exponent >= kMaxExponent) return kBucketCount - 1;
  const int shift = exponent - kSubBucketBits;
  const auto top = static_cast<std::int64_t>(value >> shift);  // in [kSubBuckets, 2 kSubBuckets)
  return static_cast<std::size_t>(kLinearBuckets + shift * kSubBuckets + (top - kSubBuckets));
}

std::int64_t LoopStatistics::bucketLower(std::size_t index) noexcept {
  const auto i = static_cast<std::int64_t>(index);
  if (i < kLinearBuckets) return i;
  const std::int64_t j = i - kLinearBuckets;
  const std::int64_t shift = j / kSubBuckets;
  const std::int64_t top = j % kSubBuckets + kSubBuckets;
  return top << shift;
}

std::int64_t LoopStatistics::bucketUpper(std::size_t index) noexcept {
  const auto i = static_cast<std::int64_t>(index);
  if (i < kLinearBuckets) return i + 1;
  const std::int64_t shift = (i - kLinearBuckets) / kSubBuckets;
  return bucketLower(index) + (std::int64_t{1} << shift);
}

void LoopStatistics::recordCycle(std::int64_t compute_ns, bool control_update) noexcept {
  compute_ns = std::max<std::int64_t>(compute_ns, 0);
  if (compute_ns < compute_min_ns_.load(std::memory_order_relaxed)) {
    compute_min_ns_.store(compute_ns, std::memory_order_relaxed);
  }
  if (compute_ns > compute_max_ns_.load(std::memory_order_relaxed)) {
    compute_max_ns_.store(compute_ns, std::memory_order_relaxed);
  }
  compute_sum_ns_.store(compute_sum_ns_.load(std::memory_order_relaxed) + compute_ns,
                        std::memory_order_relaxed);
  bump(histogram_[bucketIndex(compute_ns)]);
  // Then counted like any cycle, last (its release store): a reader that sees
  // this cycle counted sees its cost too.
  recordUntimedCycle(control_update);
}

void LoopStatistics::setElapsed(double sim_time_s, std::int64_t wall_time_ns) noexcept {
  sim_time_s_.store(sim_time_s, std::memory_order_relaxed);
  wall_time_ns_.store(wall_time_ns, std::memory_order_relaxed);
}

void LoopStatistics::reset() noexcept {
  cycles_.store(0, std::memory_order_relaxed);
  control_updates_.store(0, std::memory_order_relaxed);
  sim_time_s_.store(0.0, std::memory_order_relaxed);
  wall_time_ns_.store(0, std::memory_order_relaxed);
  compute_min_ns_.store(kUnsetMin, std::memory_order_relaxed);
  compute_max_ns_.store(0, std::memory_order_relaxed);
  compute_sum_ns_.store(0, std::memory_order_relaxed);
  overruns_.store(0, std::memory_order_relaxed);
  schedule_resets_.store(0, std::memory_order_relaxed);
  hardware_errors_.store(0, std::memory_order_relaxed);
  for (auto& bucket : histogram_) bucket.store(0, std::memory_order_relaxed);
}

namespace {

using Counts = std::array<std::uint64_t, LoopStatistics::kBucketCount>;

// The value below which a fraction q of `total` counted values lie (bucket
// midpoint, clamped to [min_ns, max_ns]), from one copy of the histogram.
double percentileOf(const Counts& counts, double q, std::uint64_t total, std::int64_t min_ns,
                    std::int64_t max_ns) noexcept {
  if (total == 0) return 0.0;
  // The smallest bucket holding at least ceil(q * total) of the values.
  const auto rank = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(total))));
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    seen += counts[i];
    if (seen >= rank) {
      const double middle =
          0.5 * static_cast<double>(LoopStatistics::bucketLower(i) + LoopStatistics::bucketUpper(i) - 1);
      return std::clamp(middle, static_cast<double>(min_ns), static_cast<double>(max_ns)) * kSecondsPerNs;
    }
  }
  return static_cast<double>(max_ns) * kSecondsPerNs;
}

}  // namespace

double LoopStatistics::percentileSeconds(double q, std::uint64_t total, std::int64_t min_ns,
                                         std::int64_t max_ns) const noexcept {
  Counts counts;
  for (std::size_t i = 0; i < kBucketCount; ++i) counts[i] = histogram_[i].load(std::memory_order_relaxed);
  return percentileOf(counts, q, total, min_ns, max_ns);
}

LoopStatisticsSnapshot LoopStatistics::snapshot() const noexcept {
  LoopStatisticsSnapshot s;
  s.cycles = cycles_.load(std::memory_order_acquire);
  s.control_updates = control_updates_.load(std::memory_order_relaxed);
  s.sim_time_s = sim_time_s_.load(std::memory_order_relaxed);
  s.wall_time_s = static_cast<double>(wall_time_ns_.load(std::memory_order_relaxed)) * kSecondsPerNs;
  s.real_time_factor = s.wall_time_s > 0.0 ? s.sim_time_s / s.wall_time_s : 0.0;
  s.overruns = overruns_.load(std::memory_order_relaxed);
  s.schedule_resets = schedule_resets_.load(std::memory_order_relaxed);
  s.hardware_errors = hardware_errors_.load(std::memory_order_relaxed);
  if (s.cycles == 0) return s;

  // One copy of the histogram, read once: its total and both percentiles come
  // from the same counts even while the writer adds cycles (reading it twice
  // could put the median above the 99th percentile).
  Counts counts;
  std::uint64_t total = 0;
  for (std::size_t i = 0; i < kBucketCount; ++i) {
    counts[i] = histogram_[i].load(std::memory_order_relaxed);
    total += counts[i];
  }
  const std::int64_t min_ns = compute_min_ns_.load(std::memory_order_relaxed);
  const std::int64_t max_ns = compute_max_ns_.load(std::memory_order_relaxed);
  const std::int64_t sum_ns = compute_sum_ns_.load(std::memory_order_relaxed);
  // (A first timed cycle counted in the histogram but not yet in the minimum
  // is still being recorded: as if it were not there yet.)
  if (total == 0 || min_ns == kUnsetMin) return s;
  s.timed_cycles = total;
  s.compute_min_s = static_cast<double>(min_ns) * kSecondsPerNs;
  s.compute_max_s = static_cast<double>(max_ns) * kSecondsPerNs;
  s.compute_mean_s = static_cast<double>(sum_ns) / static_cast<double>(total) * kSecondsPerNs;
  s.compute_p50_s = percentileOf(counts, 0.50, total, min_ns, max_ns);
  s.compute_p99_s = percentileOf(counts, 0.99, total, min_ns, max_ns);
  return s;
}

std::string LoopStatistics::summary() const { return summary(snapshot()); }

std::string LoopStatistics::summary(const LoopStatisticsSnapshot& s) {
  const std::string timed =
      s.timed_cycles == s.cycles ? std::string() : fmt::format(" ({} of {} cycles timed)", s.timed_cycles, s.cycles);
  return fmt::format(
      "loop: {} cycles ({} control updates), {:.3f} s simulated in {:.3f} s wall (real-time factor {:.3f}); "
      "compute per cycle{} min {}, mean {}, p50 {}, p99 {}, max {}; "
      "{} overruns, {} schedule resets, {} hardware errors",
      s.cycles, s.control_updates, s.sim_time_s, s.wall_time_s, s.real_time_factor, timed,
      formatDuration(s.compute_min_s), formatDuration(s.compute_mean_s), formatDuration(s.compute_p50_s),
      formatDuration(s.compute_p99_s), formatDuration(s.compute_max_s), s.overruns, s.schedule_resets,
      s.hardware_errors);
}

}  // namespace servoloop::controller_manager
