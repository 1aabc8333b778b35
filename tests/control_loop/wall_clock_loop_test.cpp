// WallClockLoop: call order, monotonic control time, deadline grid, overruns
// and stopping. Timing assertions are lower bounds or follow from the
// deadline grid alone (cycles start at start + n · period).
#include <atomic>
#include <chrono>
#include <future>
#include <thread>

#include <gtest/gtest.h>

#include "control_loop_test_support.hpp"
#include "servoloop/controller_manager/wall_clock_loop.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::controller_manager {
namespace {

using testing::EventKind;
using testing::LoopFixture;
using testing::RecordingHook;

TEST(WallClockLoop, PeriodComesFromTheManagerRate) {
  LoopFixture f(0.001, 500.0);
  WallClockLoop loop(f.hw, f.manager);
  EXPECT_DOUBLE_EQ(loop.controlPeriod().seconds, 0.002);
}

TEST(WallClockLoop, RejectsAMissingOrDisagreeingPeriod) {
  LoopFixture no_rate(0.001, 0.0);
  try {
    WallClockLoop loop(no_rate.hw, no_rate.manager);
    FAIL() << "a loop without any period was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("no cycle period"), std::string::npos) << e.what();
  }
  LoopFixture f(0.001, 1000.0);
  WallClockLoop::Options options;
  options.period = Duration(0.002);
  EXPECT_THROW(WallClockLoop(f.hw, f.manager, options), ConfigError);
  options.period = Duration(-1.0);
  EXPECT_THROW(WallClockLoop(f.hw, f.manager, options), ConfigError);
}

// step_simulation: a simulated robot standing in for hardware is stepped once
// per cycle, after write; its time step must be the period.
TEST(WallClockLoop, StepsASimulatedRobotOncePerCycleWhenAsked) {
  LoopFixture f(0.001, 1000.0);
  RecordingHook hook(f.recorder);
  WallClockLoop::Options options;
  options.cycle_hook = &hook;
  options.step_simulation = true;
  WallClockLoop loop(f.hw, f.manager, options);
  f.requestStart();
  loop.runFor(Duration(0.02));
  const LoopStatisticsSnapshot stats = loop.statistics().snapshot();
  EXPECT_GE(stats.cycles, 1u);
  EXPECT_EQ(f.hw.steps, stats.cycles);
  const std::vector<testing::Event> events = f.recorder->events();
  ASSERT_GE(events.size(), 5u);  // the first cycle: read, hook, write, step (the controller starts in it)
  EXPECT_EQ(events[2].kind, EventKind::write);
  EXPECT_EQ(events[3].kind, EventKind::step);
  EXPECT_EQ(events[4].kind, EventKind::read);

  LoopFixture coarse(0.001, 500.0);  // 2 ms cycles, 1 ms physics step
  try {
    WallClockLoop mismatched(coarse.hw, coarse.manager, options);
    FAIL() << "a time step other than the period was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("not the cycle period 0.002 s"), std::string::npos) << e.what();
  }
}

TEST(WallClockLoop, EachCycleIsReadUpdateWriteWithIncreasingTime) {
  LoopFixture f(0.001, 1000.0);
  RecordingHook hook(f.recorder);
  WallClockLoop::Options options;
  options.cycle_hook = &hook;
  WallClockLoop loop(f.hw, f.manager, options);
  f.requestStart();
  // Run until a dozen cycles are done, however loaded the machine is.
  std::atomic<bool> stop{false};
  auto running = std::async(std::launch::async, [&] { loop.run(stop); });
  while (loop.statistics().snapshot().cycles < 12) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  stop.store(true);
  running.get();

  const LoopStatisticsSnapshot stats = loop.statistics().snapshot();
  EXPECT_EQ(stats.control_updates, stats.cycles);
  EXPECT_GT(stats.real_time_factor, 0.0);
  EXPECT_EQ(f.hw.steps, 0u);  // real hardware is not stepped

  // read, hook (the first cycle only starts the controller), write; then
  // read, update, hook, write every cycle.
  const auto& events = f.recorder->events();
  ASSERT_GE(events.size(), 7u);
  EXPECT_EQ(events[0].kind, EventKind::read);
  EXPECT_EQ(events[1].kind, EventKind::hook);
  EXPECT_EQ(events[2].kind, EventKind::write);
  EXPECT_NEAR(events[1].period_s, 0.001, 1e-12);  // the first cycle gets the nominal period
  double previous_time = events[0].time_s;
  for (std::size_t i = 3; i + 3 < events.size(); i += 4) {
    EXPECT_EQ(events[i].kind, EventKind::read);
    EXPECT_EQ(events[i + 1].kind, EventKind::update);
    EXPECT_EQ(events[i + 2].kind, EventKind::hook);
    EXPECT_EQ(events[i + 3].kind, EventKind::write);
    const double t = events[i].time_s;
    EXPECT_GT(t, previous_time);
    // The period handed to update is the time since the previous cycle started.
    EXPECT_NEAR(events[i + 2].period_s, t - previous_time, 1e-9);
    EXPECT_EQ(events[i + 1].time_s, t);
    EXPECT_EQ(events[i + 3].time_s, t);
    previous_time = t;
  }
}

TEST(WallClockLoop, CyclesStartOnTheDeadlineGrid) {
  LoopFixture f(0.001, 1000.0);
  f.recorder->enabled = false;
  WallClockLoop loop(f.hw, f.manager);
  const auto start = std::chrono::steady_clock::now();
  loop.runFor(Duration(0.05));
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const LoopStatisticsSnapshot stats = loop.statistics().snapshot();
  // Cycles start on the grid start + n · 1 ms within the 50 ms run: at least
  // the first, at most 50; the last one started (cycles − 1) ms in or later.
  EXPECT_GE(stats.cycles, 1u);
  EXPECT_LE(stats.cycles, 50u);
  EXPECT_GE(wall_s, 0.001 * static_cast<double>(stats.cycles - 1));
}

TEST(WallClockLoop, RunsOneAfterAnotherStayOnOneGrid) {
  // A node runs the loop in pieces (runFor up to the next timed
  // publication). The first piece's last cycle starts at 4 ms, and its next
  // deadline, 5 ms, is past its length, so it returns right after that
  // cycle: the second piece must wait for 5 ms, not start a cycle at once.
  LoopFixture f(0.001, 1000.0);
  WallClockLoop loop(f.hw, f.manager);
  loop.runFor(Duration(0.005));
  const std::size_t first_piece = f.recorder->ofKind(EventKind::read).size();
  loop.runFor(Duration(0.005));
  const std::vector<testing::Event> reads = f.recorder->ofKind(EventKind::read);
  ASSERT_GT(first_piece, 0u);
  ASSERT_GT(reads.size(), first_piece);
  // Time counts from the first deadline (the first run's start): the cycle
  // of the deadline at 5 ms cannot start earlier, however late the cycles
  // before it woke, the first one included.
  EXPECT_GE(reads[first_piece].time_s, 0.005 - 1e-12) << "the second piece started off the first piece's grid";
  // Control time is the grid the two pieces covered, one period per
  // deadline (a cycle's or one skipped): 10 ms, whatever their cycles'
  // wake-ups, or more if the last cycle overran past the end.
  const LoopStatisticsSnapshot stats = loop.statistics().snapshot();
  EXPECT_NEAR(stats.sim_time_s, 0.001 * static_cast<double>(stats.cycles + stats.skipped_deadlines), 1e-12);
  EXPECT_GE(stats.cycles + stats.skipped_deadlines, 10u);
  // And the controllers are told the measured time since the cycle before.
  const double gap_s = reads[first_piece].time_s - reads[first_piece - 1].time_s;
  EXPECT_NEAR(reads[first_piece].period_s, gap_s, 1e-12);
  EXPECT_LE(reads.size(), 10u);  // deadlines 0–4 ms, then 5–9 ms
}

// A pause between two runs longer than the second run (the node's thread
// held up): the deadlines it missed are skipped and counted, the run still
// runs one cycle, at the first deadline ahead, and control time covers the
// deadlines skipped.
TEST(WallClockLoop, ARunThePauseBeforeItMissedWholeRunsOneCycleLate) {
  LoopFixture f(0.001, 1000.0);
  WallClockLoop loop(f.hw, f.manager);
  loop.runFor(Duration(0.003));
  const std::size_t first_piece = f.recorder->ofKind(EventKind::read).size();
  const std::uint64_t skipped_before = loop.statistics().snapshot().skipped_deadlines;
  // The pause itself is what is tested: 6 ms past the next deadline (3 ms)
  // at least, so a 2 ms run starting there has no deadline of its own left.
  std::this_thread::sleep_for(std::chrono::milliseconds(6));
  loop.runFor(Duration(0.002));
  const std::vector<testing::Event> reads = f.recorder->ofKind(EventKind::read);
  ASSERT_EQ(reads.size(), first_piece + 1);
  EXPECT_GE(reads.back().time_s, 0.009 - 1e-12);
  const LoopStatisticsSnapshot stats = loop.statistics().snapshot();
  EXPECT_GE(stats.skipped_deadlines - skipped_before, 6u);
  EXPECT_NEAR(stats.sim_time_s, 0.001 * static_cast<double>(stats.cycles + stats.skipped_deadlines), 1e-12);
}

// A stop (a hardware fault, until `control recover`) and a run after it: the
// loop resumes its grid at the first deadline from now, so control time is
// again the time since the loop's start, as the controllers' time is; the
// deadlines it stood still for are skipped, and the wall time counts the stop.
TEST(WallClockLoop, AfterAStopTheLoopResumesItsGrid) {
  LoopFixture f(0.001, 1000.0);
  WallClockLoop loop(f.hw, f.manager);
  loop.runFor(Duration(0.003));
  loop.requestStop();
  loop.runFor(Duration(0.003));  // stopped at once: the grid is left
  const std::size_t before = f.recorder->ofKind(EventKind::read).size();
  const std::uint64_t skipped_before = loop.statistics().snapshot().skipped_deadlines;
  // The stop itself is what is tested: 10 ms standing still.
  std::this_thread::sleep_for(std::chrono::milliseconds(10));
  loop.runFor(Duration(0.003));
  const std::vector<testing::Event> reads = f.recorder->ofKind(EventKind::read);
  ASSERT_GT(before, 0u);
  // The deadlines of the stop count towards the 3 ms run, as a pause's do:
  // one cycle, late (a node's run up to a publication that fell due in the
  // stop ends there, and publishes). 3 ms of grid before the stop and 10 ms
  // standing: it is at 13 ms or later.
  ASSERT_EQ(reads.size(), before + 1);
  EXPECT_GE(reads[before].time_s, 0.013 - 1e-12);
  const LoopStatisticsSnapshot stats = loop.statistics().snapshot();
  EXPECT_GE(stats.skipped_deadlines - skipped_before, 10u);
  EXPECT_NEAR(stats.sim_time_s, 0.001 * static_cast<double>(stats.cycles + stats.skipped_deadlines), 1e-12);
  // The last cycle's time (its deadline and its wake-up latency) is before
  // the control time the loop reached with it: the deadline after it, or the
  // first one ahead if it overran. (Control time that did not count the stop
  // would be 10 ms behind.)
  EXPECT_GT(stats.sim_time_s, reads.back().time_s);
  EXPECT_GE(stats.wall_time_s, 0.013);
}

TEST(WallClockLoop, SlowHardwareCountsOverrunsAndSkipsMissedDeadlines) {
  // read() takes 3 ms in a 1 ms loop: every cycle overruns, and the skipped
  // deadlines keep the cycle count at one per 3+ ms instead of a burst.
  LoopFixture f(0.001, 1000.0);
  f.recorder->enabled = false;
  f.hw.read_sleep = std::chrono::microseconds(3000);
  WallClockLoop loop(f.hw, f.manager);
  loop.runFor(Duration(0.03));
  const LoopStatisticsSnapshot stats = loop.statistics().snapshot();
  EXPECT_GE(stats.cycles, 1u);
  EXPECT_EQ(stats.overruns, stats.cycles);
  EXPECT_LE(stats.cycles, 10u);  // cycles start >= 3 ms apart within 30 ms
  EXPECT_GE(stats.compute_min_s, 0.0029999);  // read() alone sleeps 3 ms
}

TEST(WallClockLoop, RequestStopFromAnotherThreadEndsRun) {
  LoopFixture f(0.001, 1000.0);
  f.recorder->enabled = false;
  WallClockLoop loop(f.hw, f.manager);
  std::atomic<bool> never{false};
  auto running = std::async(std::launch::async, [&] { loop.run(never); });
  while (loop.statistics().snapshot().cycles < 5) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  loop.requestStop();
  ASSERT_EQ(running.wait_for(std::chrono::seconds(10)), std::future_status::ready) << "run() did not stop";
  running.get();
  EXPECT_GE(loop.statistics().snapshot().cycles, 5u);
}

TEST(WallClockLoop, HardwareErrorIsCountedAndReportedOnce) {
  LoopFixture f(0.001, 1000.0);
  f.recorder->enabled = false;
  f.hw.write_script.from = 2;  // every write from the third on fails
  WallClockLoop loop(f.hw, f.manager);
  std::atomic<bool> stop{false};
  auto running = std::async(std::launch::async, [&] { loop.run(stop); });
  while (loop.statistics().snapshot().hardware_errors < 3) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  stop.store(true);
  running.get();
  const auto report = loop.takeHardwareErrorReport();
  ASSERT_TRUE(report.has_value());
  EXPECT_EQ(report->call, HardwareCall::write);
  EXPECT_EQ(report->cycle, 2u);
  EXPECT_FALSE(loop.takeHardwareErrorReport().has_value());
  EXPECT_FALSE(loop.hardwareAskedToStop());
}

}  // namespace
}  // namespace servoloop::controller_manager

namespace servoloop::controller_manager {
namespace {

// The phases are timed separately: a read() that sleeps 2 ms shows in read's
// figures (and the cycle's), not in write's or the controller's; every cycle
// records a wake-up latency, every cycle after the first a period jitter; the
// controllers' updates are timed in one cycle in 16.
TEST(WallClockLoopStatistics, PhasesWakeUpLatencyAndJitterArePerCycle) {
  testing::LoopFixture f(0.005, 200.0);
  f.recorder->enabled = false;
  f.hw.read_sleep = std::chrono::microseconds(2000);
  WallClockLoop loop(f.hw, f.manager);
  f.requestStart();
  loop.runFor(Duration(0.1));  // 20 cycles of 5 ms
  const LoopStatisticsSnapshot s = loop.statistics().snapshot();
  ASSERT_GE(s.cycles, 10u);
  EXPECT_EQ(s.read.count, s.cycles);
  EXPECT_EQ(s.write.count, s.cycles);
  EXPECT_EQ(s.wakeup_latency.count, s.cycles);
  EXPECT_EQ(s.period_jitter.count, s.cycles - 1);
  EXPECT_GE(s.read.min_s, 0.002);  // sleep_for sleeps at least as long
  EXPECT_LT(s.write.p50_s, 0.001);
  EXPECT_GE(s.compute_min_s, s.read.min_s);
  const auto times = f.manager.updateTimes();
  ASSERT_EQ(times.size(), 1u);
  EXPECT_EQ(times[0].first, "ctrl");
  // The controller's updates are timed in the loop's cycles 0, 16, 32, … (one
  // in kUpdateTimingStride); it updated in the last `updates` cycles.
  const std::uint64_t first_update_cycle = s.cycles - f.controller()->updates;
  std::uint64_t timed_updates = 0;
  for (std::uint64_t cycle = first_update_cycle; cycle < s.cycles; ++cycle) {
    if (cycle % ControlLoop::kUpdateTimingStride == 0) ++timed_updates;
  }
  ASSERT_GE(timed_updates, 1u);
  EXPECT_EQ(times[0].second.count, timed_updates);
  EXPECT_LT(times[0].second.p50_s, 0.001);
  EXPECT_GE(s.wakeup_latency.min_s, 0.0);
  EXPECT_LE(s.wakeup_latency.p50_s, s.wakeup_latency.max_s);
}

// A reset asked from another thread happens at the start of the next cycle:
// afterwards only the cycles since are counted, controllers' times included.
TEST(WallClockLoopStatistics, ResetRequestZeroesAtTheNextCycle) {
  testing::LoopFixture f(0.002, 500.0);
  f.recorder->enabled = false;
  WallClockLoop loop(f.hw, f.manager);
  f.requestStart();
  loop.runFor(Duration(0.02));
  ASSERT_GE(loop.statistics().snapshot().cycles, 5u);
  loop.requestStatisticsReset();
  EXPECT_TRUE(loop.statistics().resetPending());
  loop.runFor(Duration(0.001));  // one cycle
  const LoopStatisticsSnapshot s = loop.statistics().snapshot();
  EXPECT_FALSE(loop.statistics().resetPending());
  EXPECT_EQ(s.cycles, 1u);
  EXPECT_EQ(s.read.count, 1u);
  EXPECT_EQ(f.manager.updateTimes()[0].second.count, 1u);
  EXPECT_GT(s.sim_time_s, 0.01);  // control time runs on
}

}  // namespace
}  // namespace servoloop::controller_manager
