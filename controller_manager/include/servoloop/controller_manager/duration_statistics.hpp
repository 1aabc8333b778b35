#pragma once
// Statistics of one kind of duration a real-time thread measures over and
// over (a cycle's compute time, a hardware read, a controller's update, the
// period's jitter): count, min, mean, max and percentiles from a histogram
// preallocated inside the object (log-linear buckets, at most 1/32 ≈ 3 %
// relative error), so recording never allocates.
//
// Threads. One writer (record, the real-time thread): lock-free,
// allocation-free. Any thread may call snapshot() at any time: every field is
// an atomic, so each value read is one the writer stored. reset() is for the
// writer's thread, or while nobody records.
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>

namespace servoloop::controller_manager {

struct DurationSnapshot {
  std::uint64_t count = 0;  // values recorded; every figure below is 0 when none
  double min_s = 0.0;
  double mean_s = 0.0;
  double p50_s = 0.0;  // from the histogram
  double p99_s = 0.0;  // from the histogram
  double max_s = 0.0;
};

// "min 3.1 us, mean 4.0 us, p50 3.9 us, p99 9.8 us, max 41.0 us".
std::string toText(const DurationSnapshot& snapshot);
// "3.1 us", "12.400 ms", "850 ns".
std::string formatDuration(double seconds);

class DurationStatistics {
 public:
  // Histogram layout: values below kLinearBuckets ns have a bucket each; above,
  // every power of two is split into kSubBuckets equal buckets, up to 2^kMaxExponent ns
  // (about 18 minutes; larger values land in the last bucket).
  static constexpr int kSubBucketBits = 5;
  static constexpr std::int64_t kSubBuckets = std::int64_t{1} << kSubBucketBits;
  static constexpr std::int64_t kLinearBuckets = kSubBuckets;
  static constexpr int kMaxExponent = 40;
  static constexpr std::size_t kBucketCount =
      static_cast<std::size_t>(kLinearBuckets + (kMaxExponent - kSubBucketBits) * kSubBuckets);

  DurationStatistics() { reset(); }
  DurationStatistics(const DurationStatistics&) = delete;
  DurationStatistics& operator=(const DurationStatistics&) = delete;

  // Writer. One value, ns (negative values count as 0).
  void record(std::int64_t value_ns) noexcept;
  // Back to no values.
  void reset() noexcept;

  // Any thread. From one read of the histogram: the count and both
  // percentiles agree even while the writer records.
  DurationSnapshot snapshot() const noexcept;

  // The histogram bucket a value (ns) falls in, and the range [lower, upper)
  // of values a bucket holds. Public for the tests of the bucket layout.
  static std::size_t bucketIndex(std::int64_t value_ns) noexcept;
  static std::int64_t bucketLower(std::size_t index) noexcept;
  static std::int64_t bucketUpper(std::size_t index) noexcept;

 private:
  std::atomic<std::int64_t> min_ns_{0};
  std::atomic<std::int64_t> max_ns_{0};
  std::atomic<std::int64_t> sum_ns_{0};
  std::array<std::atomic<std::uint64_t>, kBucketCount> histogram_{};
};

}  // namespace servoloop::controller_manager
