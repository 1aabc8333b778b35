// DurationStatistics: single-writer min/max/sum and a fixed log-linear histogram.
#include "servoloop/controller_manager/duration_statistics.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace servoloop::controller_manager {

namespace {
constexpr double kSecondsPerNs = 1e-9;
constexpr std::int64_t kUnsetMin = std::numeric_limits<std::int64_t>::max();

using Counts = std::array<std::uint64_t, DurationStatistics::kBucketCount>;

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
          0.5 * static_cast<double>(DurationStatistics::bucketLower(i) + DurationStatistics::bucketUpper(i) - 1);
      return std::clamp(middle, static_cast<double>(min_ns), static_cast<double>(max_ns)) * kSecondsPerNs;
    }
  }
  return static_cast<double>(max_ns) * kSecondsPerNs;
}
}  // namespace

std::string formatDuration(double seconds) {
  const double magnitude = std::abs(seconds);
  if (magnitude >= 1.0) return fmt::format("{:.3f} s", seconds);
  if (magnitude >= 1e-3) return fmt::format("{:.3f} ms", seconds * 1e3);
  if (magnitude >= 1e-6) return fmt::format("{:.1f} us", seconds * 1e6);
  return fmt::format("{:.0f} ns", seconds * 1e9);
}

std::string toText(const DurationSnapshot& s) {
  return fmt::format("min {}, mean {}, p50 {}, p99 {}, max {}", formatDuration(s.min_s), formatDuration(s.mean_s),
                     formatDuration(s.p50_s), formatDuration(s.p99_s), formatDuration(s.max_s));
}

std::size_t DurationStatistics::bucketIndex(std::int64_t value_ns) noexcept {
  if (value_ns < kLinearBuckets) return static_cast<std::size_t>(std::max<std::int64_t>(value_ns, 0));
  const auto value = static_cast<std::uint64_t>(value_ns);
  const int exponent = std::bit_width(value) - 1;  // floor(log2(value)) >= kSubBucketBits
  if (exponent >= kMaxExponent) return kBucketCount - 1;
  const int shift = exponent - kSubBucketBits;
  const auto top = static_cast<std::int64_t>(value >> shift);  // in [kSubBuckets, 2 kSubBuckets)
  return static_cast<std::size_t>(kLinearBuckets + shift * kSubBuckets + (top - kSubBuckets));
}

std::int64_t DurationStatistics::bucketLower(std::size_t index) noexcept {
  const auto i = static_cast<std::int64_t>(index);
  if (i < kLinearBuckets) return i;
  const std::int64_t j = i - kLinearBuckets;
  const std::int64_t shift = j / kSubBuckets;
  const std::int64_t top = j % kSubBuckets + kSubBuckets;
  return top << shift;
}

std::int64_t DurationStatistics::bucketUpper(std::size_t index) noexcept {
  const auto i = static_cast<std::int64_t>(index);
  if (i < kLinearBuckets) return i + 1;
  const std::int64_t shift = (i - kLinearBuckets) / kSubBuckets;
  return bucketLower(index) + (std::int64_t{1} << shift);
}

void DurationStatistics::record(std::int64_t value_ns) noexcept {
  value_ns = std::max<std::int64_t>(value_ns, 0);
  // Single writer: a relaxed load and a release store is an atomic update
  // here. Every store is a release (free on x86): a reader that sees the count
  // sees the min/max/sum before it, and a reader that sees any of them sees
  // the LoopStatistics group it belongs to open (its sequence lock needs no fence).
  if (value_ns < min_ns_.load(std::memory_order_relaxed)) min_ns_.store(value_ns, std::memory_order_release);
  if (value_ns > max_ns_.load(std::memory_order_relaxed)) max_ns_.store(value_ns, std::memory_order_release);
  sum_ns_.store(sum_ns_.load(std::memory_order_relaxed) + value_ns, std::memory_order_release);
  std::atomic<std::uint64_t>& bucket = histogram_[bucketIndex(value_ns)];
  bucket.store(bucket.load(std::memory_order_relaxed) + 1, std::memory_order_release);
}

void DurationStatistics::reset() noexcept {
  min_ns_.store(kUnsetMin, std::memory_order_release);
  max_ns_.store(0, std::memory_order_release);
  sum_ns_.store(0, std::memory_order_release);
  for (auto& bucket : histogram_) bucket.store(0, std::memory_order_release);
}

DurationSnapshot DurationStatistics::snapshot() const noexcept {
  DurationSnapshot s;
  Counts counts;
  std::uint64_t total = 0;
  for (std::size_t i = 0; i < kBucketCount; ++i) {
    counts[i] = histogram_[i].load(std::memory_order_acquire);
    total += counts[i];
  }
  const std::int64_t min_ns = min_ns_.load(std::memory_order_acquire);
  const std::int64_t max_ns = max_ns_.load(std::memory_order_acquire);
  const std::int64_t sum_ns = sum_ns_.load(std::memory_order_acquire);
  // (A first value counted in the histogram but not yet in the minimum is
  // still being recorded: as if it were not there yet.)
  if (total == 0 || min_ns == kUnsetMin) return s;
  s.count = total;
  s.min_s = static_cast<double>(min_ns) * kSecondsPerNs;
  s.max_s = static_cast<double>(max_ns) * kSecondsPerNs;
  s.mean_s = static_cast<double>(sum_ns) / static_cast<double>(total) * kSecondsPerNs;
  s.p50_s = percentileOf(counts, 0.50, total, min_ns, max_ns);
  s.p99_s = percentileOf(counts, 0.99, total, min_ns, max_ns);
  return s;
}

}  // namespace servoloop::controller_manager
