// LoopStatistics: the histogram's bucket layout, percentiles of a known
// distribution, and reading while another thread records.
#include <atomic>
#include <cmath>
#include <thread>

#include <gtest/gtest.h>

#include "servoloop/controller_manager/loop_statistics.hpp"

namespace servoloop::controller_manager {
namespace {

TEST(LoopStatistics, BucketsTileTheRangeWithAtMostOneThirtySecondRelativeWidth) {
  std::int64_t expected_lower = 0;
  for (std::size_t i = 0; i < LoopStatistics::kBucketCount; ++i) {
    const std::int64_t lower = LoopStatistics::bucketLower(i);
    const std::int64_t upper = LoopStatistics::bucketUpper(i);
    ASSERT_EQ(lower, expected_lower) << "bucket " << i;  // no gaps, no overlaps
    ASSERT_GT(upper, lower);
    EXPECT_EQ(LoopStatistics::bucketIndex(lower), i);
    EXPECT_EQ(LoopStatistics::bucketIndex(upper - 1), i);
    if (lower >= LoopStatistics::kLinearBuckets) {
      EXPECT_LE(static_cast<double>(upper - lower) / static_cast<double>(lower), 1.0 / 32.0);
    }
    expected_lower = upper;
  }
  // Beyond the range: the last bucket.
  EXPECT_EQ(LoopStatistics::bucketIndex(std::int64_t{1} << 50), LoopStatistics::kBucketCount - 1);
  EXPECT_EQ(LoopStatistics::bucketIndex(-5), 0u);
}

TEST(LoopStatistics, PercentilesOfAUniformDistribution) {
  // Compute costs 1, 2, ..., 1000 us: min 1 us, max 1000 us, mean 500.5 us,
  // p50 = 500 us and p99 = 990 us (nearest rank), within the bucket width.
  LoopStatistics stats;
  for (int k = 1000; k >= 1; --k) stats.recordCycle(std::int64_t{k} * 1000, k % 2 == 0);
  const LoopStatisticsSnapshot s = stats.snapshot();
  EXPECT_EQ(s.cycles, 1000u);
  EXPECT_EQ(s.control_updates, 500u);
  EXPECT_DOUBLE_EQ(s.compute_min_s, 1e-6);
  EXPECT_DOUBLE_EQ(s.compute_max_s, 1e-3);
  EXPECT_NEAR(s.compute_mean_s, 500.5e-6, 1e-15);
  EXPECT_NEAR(s.compute_p50_s, 500e-6, 500e-6 / 32.0);
  EXPECT_NEAR(s.compute_p99_s, 990e-6, 990e-6 / 32.0);
}

TEST(LoopStatistics, UntimedCyclesAreCountedWithoutACost) {
  // Cycles of 2, 4 and 9 us timed, two more only counted: the compute
  // figures are those of the three timed ones.
  LoopStatistics stats;
  stats.recordCycle(2000, true);
  stats.recordUntimedCycle(false);
  stats.recordCycle(4000, false);
  stats.recordUntimedCycle(true);
  stats.recordCycle(9000, true);
  const LoopStatisticsSnapshot s = stats.snapshot();
  EXPECT_EQ(s.cycles, 5u);
  EXPECT_EQ(s.control_updates, 3u);
  EXPECT_EQ(s.timed_cycles, 3u);
  EXPECT_DOUBLE_EQ(s.compute_min_s, 2e-6);
  EXPECT_DOUBLE_EQ(s.compute_max_s, 9e-6);
  EXPECT_NEAR(s.compute_mean_s, 5e-6, 1e-15);
  const std::string summary = stats.summary();
  EXPECT_NE(summary.find("compute per cycle (3 of 5 cycles timed) min 2.0 us"), std::string::npos) << summary;

  // Counted only: no compute figures at all.
  LoopStatistics untimed;
  untimed.recordUntimedCycle(true);
  EXPECT_EQ(untimed.snapshot().cycles, 1u);
  EXPECT_EQ(untimed.snapshot().timed_cycles, 0u);
  EXPECT_EQ(untimed.snapshot().compute_max_s, 0.0);
}

TEST(LoopStatistics, EmptyAndElapsed) {
  LoopStatistics stats;
  LoopStatisticsSnapshot s = stats.snapshot();
  EXPECT_EQ(s.cycles, 0u);
  EXPECT_EQ(s.compute_min_s, 0.0);
  EXPECT_EQ(s.real_time_factor, 0.0);
  stats.setElapsed(2.0, 4'000'000'000);
  stats.recordOverrun();
  stats.recordScheduleReset();
  stats.recordHardwareError();
  s = stats.snapshot();
  EXPECT_DOUBLE_EQ(s.real_time_factor, 0.5);
  EXPECT_EQ(s.overruns, 1u);
  EXPECT_EQ(s.schedule_resets, 1u);
  EXPECT_EQ(s.hardware_errors, 1u);
  const std::string summary = stats.summary();
  EXPECT_NE(summary.find("2.000 s simulated in 4.000 s wall (real-time factor 0.500)"), std::string::npos)
      << summary;
  stats.reset();
  EXPECT_EQ(stats.snapshot().overruns, 0u);
}

TEST(LoopStatistics, SnapshotsFromAnotherThreadAreConsistentWhileRecording) {
  LoopStatistics stats;
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (int k = 0; k < 200000; ++k) stats.recordCycle(1000 + k % 5000, true);
    done.store(true);
  });
  // Checked after the join, so a failure cannot leave the writer running.
  std::uint64_t previous_cycles = 0;
  int snapshots = 0;
  int inconsistent = 0;
  while (!done.load() || snapshots == 0) {
    const LoopStatisticsSnapshot s = stats.snapshot();
    if (s.cycles < previous_cycles) ++inconsistent;
    previous_cycles = s.cycles;
    // Recorded costs lie in [1000, 5999] ns.
    if (s.cycles > 0 && (s.compute_min_s < 999.5e-9 || s.compute_max_s > 5999.5e-9 ||
                         s.compute_p50_s > s.compute_p99_s)) {
      ++inconsistent;
    }
    ++snapshots;
  }
  writer.join();
  EXPECT_EQ(inconsistent, 0) << "of " << snapshots << " snapshots";
  EXPECT_EQ(stats.snapshot().cycles, 200000u);
}

}  // namespace
}  // namespace servoloop::controller_manager

namespace servoloop::controller_manager {
namespace {

TEST(DurationStatistics, FiguresOfAKnownSetAndTheirText) {
  // 10, 20, ..., 1000 us: mean 505 us, p50 500 us, p99 990 us (nearest rank).
  DurationStatistics d;
  EXPECT_EQ(d.snapshot().count, 0u);
  for (int k = 100; k >= 1; --k) d.record(std::int64_t{k} * 10000);
  const DurationSnapshot s = d.snapshot();
  EXPECT_EQ(s.count, 100u);
  EXPECT_DOUBLE_EQ(s.min_s, 10e-6);
  EXPECT_DOUBLE_EQ(s.max_s, 1e-3);
  EXPECT_NEAR(s.mean_s, 505e-6, 1e-15);
  EXPECT_NEAR(s.p50_s, 500e-6, 500e-6 / 32.0);
  EXPECT_NEAR(s.p99_s, 990e-6, 990e-6 / 32.0);
  EXPECT_EQ(toText(DurationSnapshot{3, 850e-9, 2.5e-6, 2e-6, 12.4e-3, 1.5}),
            "min 850 ns, mean 2.5 us, p50 2.0 us, p99 12.400 ms, max 1.500 s");
  d.reset();
  EXPECT_EQ(d.snapshot().count, 0u);
  d.record(-5);  // a clock step backwards counts as 0
  EXPECT_EQ(d.snapshot().max_s, 0.0);
}

}  // namespace
}  // namespace servoloop::controller_manager
