// LoopStatistics: the histogram's bucket layout, percentiles of a known
// distribution, and reading while another thread records (whole cycles).
#include <atomic>
#include <chrono>
#include <cmath>
#include <string>
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

TEST(LoopStatistics, ASnapshotShowsACycleWholeOrNotAtAll) {
  // The writer records cycles as a wall-clock loop does — wake-up latency,
  // read, write, the cycle, its elapsed times — each cycle one group, and
  // waits after each for the reader's next snapshot (or 10 ms), so snapshots
  // keep landing on open groups. Every snapshot must show whole cycles: as
  // many latencies, reads and writes as cycles, and 1 ms of control time per
  // cycle. (Read field by field, a snapshot overlapping a group would count
  // a latency, a read or a write ahead of its cycle.)
  constexpr std::uint64_t kCycles = 2000;
  LoopStatistics stats;
  std::atomic<std::uint64_t> snapshots_taken{0};
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (std::uint64_t k = 0; k < kCycles; ++k) {
      const std::uint64_t seen = snapshots_taken.load();
      stats.beginUpdate();
      stats.recordWakeupLatency(20'000);
      stats.recordRead(3'000);
      // The work of the cycle: a few microseconds inside the group.
      const auto work_end = std::chrono::steady_clock::now() + std::chrono::microseconds(3);
      while (std::chrono::steady_clock::now() < work_end) {}
      stats.recordWrite(2'000);
      stats.recordCycle(9'000, true);
      stats.setElapsed(static_cast<double>(k + 1) * 1e-3, static_cast<std::int64_t>(k + 1) * 1'000'000);
      stats.endUpdate();
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::milliseconds(10);
      while (snapshots_taken.load() == seen && std::chrono::steady_clock::now() < give_up) std::this_thread::yield();
    }
    done.store(true);
  });
  // Checked after the join, so a failure cannot leave the writer running.
  std::uint64_t mid_run = 0;
  std::uint64_t torn = 0;
  std::string first_torn;
  while (!done.load()) {
    const LoopStatisticsSnapshot s = stats.snapshot(std::chrono::seconds(10));
    snapshots_taken.fetch_add(1);
    if (s.cycles > 0 && s.cycles < kCycles) ++mid_run;
    const bool whole = s.wakeup_latency.count == s.cycles && s.read.count == s.cycles &&
                       s.write.count == s.cycles && s.timed_cycles == s.cycles &&
                       std::abs(s.sim_time_s - static_cast<double>(s.cycles) * 1e-3) < 1e-9;
    if (!whole && torn++ == 0) {
      first_torn = std::to_string(s.cycles) + " cycles, " + std::to_string(s.wakeup_latency.count) +
                   " latencies, " + std::to_string(s.read.count) + " reads, " + std::to_string(s.write.count) +
                   " writes, " + std::to_string(s.sim_time_s) + " s";
    }
  }
  writer.join();
  EXPECT_EQ(torn, 0u) << "first: " << first_torn;
  EXPECT_GE(mid_run, kCycles / 4) << "snapshots taken while the writer ran";
  EXPECT_EQ(stats.snapshot().wakeup_latency.count, kCycles);
}

TEST(LoopStatistics, ASnapshotDoesNotWaitLongerThanAskedForAGroupLeftOpen) {
  // A writer stuck inside a cycle (a hardware read that hangs) holds its group
  // open: the reader gives up after its wait and reads the figures as they are.
  LoopStatistics stats;
  stats.recordCycle(1'000, true);
  stats.beginUpdate();
  stats.recordWakeupLatency(5'000);
  const auto start = std::chrono::steady_clock::now();
  const LoopStatisticsSnapshot s = stats.snapshot(std::chrono::milliseconds(20));
  const auto waited = std::chrono::steady_clock::now() - start;
  EXPECT_GE(waited, std::chrono::milliseconds(20));
  EXPECT_EQ(s.cycles, 1u);
  EXPECT_EQ(s.wakeup_latency.count, 1u);  // the open cycle's, as it is
  stats.recordCycle(1'000, true);
  stats.endUpdate();
  EXPECT_EQ(stats.snapshot(std::chrono::milliseconds(0)).cycles, 2u);
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
