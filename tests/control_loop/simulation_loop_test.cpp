// SimulationLoop: the order of calls in a cycle, the control period as a
// multiple of the physics step, exact simulated time, pacing, stopping and
// hardware errors — against the fake simulated robot of the support header.
#include <atomic>
#include <chrono>
#include <cmath>
#include <future>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "control_loop_test_support.hpp"
#include "servoloop/controller_manager/simulation_loop.hpp"
#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::controller_manager {
namespace {

using testing::EventKind;
using testing::LoopFixture;
using testing::RecordingHook;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(SimulationLoop, EachCycleIsReadUpdateWriteStepAtTheCycleTime) {
  LoopFixture f(0.001);
  RecordingHook hook(f.recorder);
  SimulationLoop::Options options;
  options.cycle_hook = &hook;
  SimulationLoop loop(f.hw, f.manager, options);
  EXPECT_DOUBLE_EQ(loop.controlPeriod().seconds, 0.001);  // defaults to the physics step
  EXPECT_EQ(loop.stepsPerControlUpdate(), 1u);

  f.requestStart();
  EXPECT_EQ(loop.cycleOnce(), ReturnType::ok);  // carries out the start: no controller update yet
  ASSERT_NE(f.controller(), nullptr);
  EXPECT_TRUE(f.controller()->isRunning());
  EXPECT_EQ(f.recorder->sequence(), "read hook write step");

  f.recorder->clear();
  for (int i = 0; i < 3; ++i) EXPECT_EQ(loop.cycleOnce(), ReturnType::ok);
  EXPECT_EQ(f.recorder->sequence(),
            "read update hook write step read update hook write step read update hook write step");
  const auto& events = f.recorder->events();
  ASSERT_EQ(events.size(), 15u);
  for (std::size_t cycle = 0; cycle < 3; ++cycle) {
    const double t = 0.001 * static_cast<double>(cycle + 1);
    for (std::size_t k = 0; k < 5; ++k) {
      const auto& e = events[cycle * 5 + k];
      EXPECT_NEAR(e.time_s, t, 1e-12) << "cycle " << cycle << " call " << testing::toString(e.kind);
      if (e.kind != EventKind::step) {
        EXPECT_NEAR(e.period_s, 0.001, 1e-12);
      }
    }
    // The command the controller just computed reaches the hardware in the same cycle.
    EXPECT_DOUBLE_EQ(events[cycle * 5 + 3].command, 2.5);
  }
  EXPECT_EQ(f.hw.steps, 4u);
  EXPECT_EQ(loop.stepsTaken(), 4u);
}

TEST(SimulationLoop, ManagerUpdatesEveryKthStepWithPeriodKDtWhileCommandsAreWrittenEveryStep) {
  // A 250 Hz manager over a 1 ms physics step: k = 4.
  LoopFixture f(0.001, 250.0);
  RecordingHook hook(f.recorder);
  SimulationLoop::Options options;
  options.cycle_hook = &hook;
  SimulationLoop loop(f.hw, f.manager, options);
  ASSERT_EQ(loop.stepsPerControlUpdate(), 4u);
  EXPECT_DOUBLE_EQ(loop.controlPeriod().seconds, 0.004);

  f.requestStart();
  loop.runFor(Duration(0.044));  // 44 physics steps

  EXPECT_EQ(f.hw.steps, 44u);
  EXPECT_EQ(f.hw.reads, 44u);
  EXPECT_EQ(f.hw.writes, 44u);
  const auto hooks = f.recorder->ofKind(EventKind::hook);
  ASSERT_EQ(hooks.size(), 11u);  // steps 0, 4, ..., 40
  for (std::size_t i = 0; i < hooks.size(); ++i) {
    EXPECT_NEAR(hooks[i].time_s, 0.004 * static_cast<double>(i), 1e-12);
    EXPECT_DOUBLE_EQ(hooks[i].period_s, 4 * 0.001);
  }
  // The controller started at step 0 and updates from step 4 on, each time
  // with the control time since its previous update.
  const auto updates = f.recorder->ofKind(EventKind::update);
  ASSERT_EQ(updates.size(), 10u);
  for (std::size_t i = 0; i < updates.size(); ++i) {
    EXPECT_NEAR(updates[i].time_s, 0.004 * static_cast<double>(i + 1), 1e-12);
    EXPECT_NEAR(updates[i].period_s, 0.004, 1e-12);
  }
  // Every physics step writes; from the first update on, the controller's
  // command is held and written on the steps between updates.
  const auto writes = f.recorder->ofKind(EventKind::write);
  ASSERT_EQ(writes.size(), 44u);
  for (std::size_t step = 0; step < writes.size(); ++step) {
    EXPECT_DOUBLE_EQ(writes[step].command, step < 4 ? 0.0 : 2.5) << "step " << step;
    EXPECT_NEAR(writes[step].period_s, 0.001, 1e-15);
  }
  const LoopStatisticsSnapshot stats = loop.statistics().snapshot();
  EXPECT_EQ(stats.cycles, 44u);
  EXPECT_EQ(stats.control_updates, 11u);
}

TEST(SimulationLoop, ExplicitControlPeriodOfThreeStepsWithoutManagerRate) {
  LoopFixture f(0.002);
  RecordingHook hook(f.recorder);
  SimulationLoop::Options options;
  options.control_period = Duration(0.006);
  options.cycle_hook = &hook;
  SimulationLoop loop(f.hw, f.manager, options);
  EXPECT_EQ(loop.stepsPerControlUpdate(), 3u);
  loop.runFor(Duration(0.03));  // 15 steps: updates at steps 0, 3, 6, 9, 12
  EXPECT_EQ(f.hw.steps, 15u);
  EXPECT_EQ(hook.calls, 5u);
}

TEST(SimulationLoop, RunForOneSecondAtOneMillisecondIsExactlyAThousandSteps) {
  LoopFixture f(0.001);
  SimulationLoop loop(f.hw, f.manager);
  f.requestStart();
  loop.runFor(Duration(1.0));
  EXPECT_EQ(f.hw.steps, 1000u);
  EXPECT_EQ(loop.stepsTaken(), 1000u);
  EXPECT_DOUBLE_EQ(f.hw.simTime().seconds, 1.0);
  const LoopStatisticsSnapshot stats = loop.statistics().snapshot();
  EXPECT_EQ(stats.cycles, 1000u);
  EXPECT_DOUBLE_EQ(stats.sim_time_s, 1.0);
  // A second run continues the simulated time.
  loop.runFor(Duration(0.1));
  EXPECT_EQ(f.hw.steps, 1100u);
  EXPECT_DOUBLE_EQ(loop.statistics().snapshot().sim_time_s, 1.1);
}

TEST(SimulationLoop, UnitInertiaUnderConstantEffortFollowsTheEulerSolution) {
  // The controller holds effort 2.5 from its first update (step 1 of 1000);
  // semi-implicit Euler of x'' = 2.5 over n = 999 steps of h gives
  // v = 2.5 n h and x = 2.5 h^2 n (n + 1) / 2 — checks that commands reach the
  // hardware in the cycle they are computed and that every step is taken once.
  LoopFixture f(0.001);
  SimulationLoop loop(f.hw, f.manager);
  f.requestStart();
  loop.runFor(Duration(1.0));
  const double h = 0.001;
  const double n = 999.0;
  EXPECT_NEAR(f.hw.velocity, 2.5 * n * h, 1e-12);
  EXPECT_NEAR(f.hw.position, 2.5 * h * h * n * (n + 1.0) / 2.0, 1e-12);
}

TEST(SimulationLoop, RejectsAControlPeriodThatIsNotAMultipleOfThePhysicsStep) {
  LoopFixture f(0.001);
  SimulationLoop::Options options;
  options.control_period = Duration(0.0025);
  try {
    SimulationLoop loop(f.hw, f.manager, options);
    FAIL() << "a 2.5 ms control period over a 1 ms step was accepted";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_TRUE(contains(what, "control period 0.0025 s")) << what;
    EXPECT_TRUE(contains(what, "physics time step 0.001 s")) << what;
    EXPECT_TRUE(contains(what, "not an integer multiple")) << what;
    EXPECT_TRUE(contains(what, "0.002 s or 0.003 s")) << what;
  }
  // Shorter than one step is no multiple either.
  options.control_period = Duration(0.0005);
  EXPECT_THROW(SimulationLoop(f.hw, f.manager, options), ConfigError);
}

TEST(SimulationLoop, RejectsAManagerRateThatIsNotAMultipleOfThePhysicsStep) {
  LoopFixture f(0.001, 400.0);  // 2.5 ms
  try {
    SimulationLoop loop(f.hw, f.manager);
    FAIL() << "a 400 Hz manager over a 1 ms step was accepted";
  } catch (const ConfigError& e) {
    EXPECT_TRUE(contains(e.what(), "control period 0.0025 s")) << e.what();
  }
}

TEST(SimulationLoop, RejectsAControlPeriodThatDisagreesWithTheManagerRate) {
  LoopFixture f(0.001, 1000.0);
  SimulationLoop::Options options;
  options.control_period = Duration(0.002);
  try {
    SimulationLoop loop(f.hw, f.manager, options);
    FAIL() << "control period 2 ms with a 1000 Hz manager was accepted";
  } catch (const ConfigError& e) {
    EXPECT_TRUE(contains(e.what(), "differs from the controller manager's update rate 1000 Hz")) << e.what();
  }
}

TEST(SimulationLoop, RejectsANegativeRealTimeFactorAndNegativeRunTime) {
  LoopFixture f(0.001);
  SimulationLoop::Options options;
  options.real_time_factor = -1.0;
  EXPECT_THROW(SimulationLoop(f.hw, f.manager, options), ConfigError);
  SimulationLoop loop(f.hw, f.manager);
  EXPECT_THROW(loop.runFor(Duration(-0.1)), Error);
  EXPECT_EQ(f.hw.steps, 0u);
}

TEST(SimulationLoop, RealTimeFactorOneTakesAtLeastTheSimulatedTime) {
  LoopFixture f(0.001);
  SimulationLoop::Options options;
  options.real_time_factor = 1.0;
  SimulationLoop loop(f.hw, f.manager, options);
  f.requestStart();
  const auto start = std::chrono::steady_clock::now();
  loop.runFor(Duration(0.2));
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(f.hw.steps, 200u);
  EXPECT_GE(wall_s, 0.2);
  const LoopStatisticsSnapshot stats = loop.statistics().snapshot();
  EXPECT_GE(stats.wall_time_s, 0.2);
  EXPECT_GT(stats.real_time_factor, 0.0);
  EXPECT_LE(stats.real_time_factor, 1.0);  // paced: simulated time never runs ahead of wall time
}

TEST(SimulationLoop, RealTimeFactorTwoTakesAtLeastHalfTheSimulatedTime) {
  LoopFixture f(0.001);
  SimulationLoop::Options options;
  options.real_time_factor = 2.0;
  SimulationLoop loop(f.hw, f.manager, options);
  const auto start = std::chrono::steady_clock::now();
  loop.runFor(Duration(0.2));
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(wall_s, 0.1);
}

// A paced loop sleeps most of each step; a snapshot taken meanwhile shows the
// control time of the steps it counts (1 ms each), not one step behind.
TEST(SimulationLoop, APacedLoopsSnapshotsCountItsStepsAndTheirTime) {
  LoopFixture f(0.001);
  f.recorder->enabled = false;
  SimulationLoop::Options options;
  options.real_time_factor = 1.0;
  SimulationLoop loop(f.hw, f.manager, options);
  auto running = std::async(std::launch::async, [&] { loop.runFor(Duration(0.2)); });
  std::uint64_t mid_run = 0;
  std::uint64_t off = 0;
  std::string first_off;
  while (running.wait_for(std::chrono::milliseconds(0)) != std::future_status::ready) {
    const LoopStatisticsSnapshot s = loop.statistics().snapshot(std::chrono::seconds(10));
    if (s.cycles == 0) continue;
    ++mid_run;
    if (std::abs(s.sim_time_s - 0.001 * static_cast<double>(s.cycles)) > 1e-12 && off++ == 0) {
      first_off = std::to_string(s.cycles) + " cycles, " + std::to_string(s.sim_time_s) + " s";
    }
    std::this_thread::sleep_for(std::chrono::microseconds(200));  // a few snapshots per step
  }
  running.get();
  EXPECT_GT(mid_run, 0u);
  EXPECT_EQ(off, 0u) << "of " << mid_run << "; first: " << first_off;
}

TEST(SimulationLoop, PacedLoopThatStallsDropsTheBacklogInsteadOfBursting) {
  // Step 50 stalls 30 ms: 29 steps of wall time late, beyond the 10-step
  // catch-up bound, so the schedule restarts from the end of that cycle.
  LoopFixture f(0.001);
  f.hw.stall_at_step = 50;
  f.hw.stall = std::chrono::milliseconds(30);
  SimulationLoop::Options options;
  options.real_time_factor = 1.0;
  SimulationLoop loop(f.hw, f.manager, options);
  const auto start = std::chrono::steady_clock::now();
  loop.runFor(Duration(0.1));
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const LoopStatisticsSnapshot stats = loop.statistics().snapshot();
  EXPECT_GE(stats.overruns, 1u);
  EXPECT_GE(stats.schedule_resets, 1u);
  // With the backlog dropped, the 49 steps after the stall are paced again:
  // 51 ms before and through the stall's deadline plus 30 ms stall plus 49 ms.
  EXPECT_GE(wall_s, 0.05 + 0.03 + 0.049);
}

TEST(SimulationLoop, FreeRunStatisticsAreConsistent) {
  LoopFixture f(0.001);
  SimulationLoop loop(f.hw, f.manager);
  f.requestStart();
  loop.runFor(Duration(0.5));
  const LoopStatisticsSnapshot s = loop.statistics().snapshot();
  EXPECT_EQ(s.cycles, 500u);
  EXPECT_EQ(s.control_updates, 500u);
  EXPECT_DOUBLE_EQ(s.sim_time_s, 0.5);
  EXPECT_GT(s.wall_time_s, 0.0);
  EXPECT_GT(s.real_time_factor, 0.0);
  EXPECT_DOUBLE_EQ(s.real_time_factor, s.sim_time_s / s.wall_time_s);
  EXPECT_GT(s.compute_max_s, 0.0);
  EXPECT_LE(s.compute_min_s, s.compute_p50_s);
  EXPECT_LE(s.compute_p50_s, s.compute_p99_s);
  EXPECT_LE(s.compute_p99_s, s.compute_max_s);
  EXPECT_LE(s.compute_min_s, s.compute_mean_s);
  EXPECT_LE(s.compute_mean_s, s.compute_max_s);
  // One cycle in 16 is timed: cycles 0, 16, ..., 496.
  EXPECT_EQ(SimulationLoop::kFreeRunningTimingStride, 16u);
  EXPECT_EQ(s.timed_cycles, 32u);
  EXPECT_LE(s.compute_mean_s * 32.0, s.wall_time_s + 1e-9);  // the timed cycles are part of the wall time
  EXPECT_EQ(s.overruns, 0u);  // free-running has no deadlines
  EXPECT_EQ(s.hardware_errors, 0u);
  const std::string summary = loop.statistics().summary();
  EXPECT_TRUE(contains(summary, "500 cycles (500 control updates)")) << summary;
  EXPECT_TRUE(contains(summary, "(32 of 500 cycles timed)")) << summary;
  EXPECT_TRUE(contains(summary, "0.500 s simulated")) << summary;
  EXPECT_TRUE(contains(summary, "0 hardware errors")) << summary;
}

TEST(SimulationLoop, TheTimingStrideRunsOnAcrossShortRuns) {
  // A node runs a free loop 10 steps at a time: cycles 0, 16, 32 and 48 of
  // the 50 are timed, not the first of every run.
  LoopFixture f(0.001);
  SimulationLoop loop(f.hw, f.manager);
  f.requestStart();
  for (int run = 0; run < 5; ++run) loop.runFor(Duration(0.01));
  const LoopStatisticsSnapshot s = loop.statistics().snapshot();
  EXPECT_EQ(s.cycles, 50u);
  EXPECT_EQ(s.timed_cycles, 4u);
  EXPECT_DOUBLE_EQ(s.sim_time_s, 0.05);
}

TEST(SimulationLoop, RequestStopFromAnotherThreadEndsRun) {
  LoopFixture f(0.001);
  f.recorder->enabled = false;
  SimulationLoop::Options options;
  options.real_time_factor = 10.0;  // paced, so the run cannot finish by accident
  SimulationLoop loop(f.hw, f.manager, options);
  std::atomic<bool> never{false};
  auto running = std::async(std::launch::async, [&] { loop.run(never); });
  while (loop.stepsTaken() < 20) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  loop.requestStop();
  ASSERT_EQ(running.wait_for(std::chrono::seconds(10)), std::future_status::ready) << "run() did not stop";
  running.get();
  const std::uint64_t steps_at_stop = loop.stepsTaken();
  EXPECT_GE(steps_at_stop, 20u);
  // The request was consumed by that run: the next one runs.
  loop.runFor(Duration(0.005));
  EXPECT_EQ(loop.stepsTaken(), steps_at_stop + 5);
}

TEST(SimulationLoop, ExternalStopFlagEndsRunAndAStopBeforeRunEndsTheNextRun) {
  LoopFixture f(0.001);
  f.recorder->enabled = false;
  SimulationLoop loop(f.hw, f.manager);
  std::atomic<bool> stop{false};
  auto running = std::async(std::launch::async, [&] { loop.run(stop); });
  while (loop.stepsTaken() < 100) std::this_thread::yield();
  stop.store(true);
  ASSERT_EQ(running.wait_for(std::chrono::seconds(10)), std::future_status::ready);
  running.get();

  const std::uint64_t steps = loop.stepsTaken();
  loop.requestStop();
  loop.runFor(Duration(1.0));
  EXPECT_EQ(loop.stepsTaken(), steps);
}

TEST(SimulationLoop, HardwareErrorIsCountedReportedOnceAndTheLoopGoesOn) {
  LoopFixture f(0.001);
  f.hw.read_script.from = 5;  // reads 5..14 fail
  f.hw.read_script.until = 15;
  SimulationLoop loop(f.hw, f.manager);
  loop.runFor(Duration(0.03));
  EXPECT_EQ(f.hw.steps, 30u);  // went on
  EXPECT_EQ(loop.statistics().snapshot().hardware_errors, 10u);
  EXPECT_FALSE(loop.hardwareAskedToStop());

  const auto report = loop.takeHardwareErrorReport();
  ASSERT_TRUE(report.has_value());
  EXPECT_EQ(report->call, HardwareCall::read);
  EXPECT_EQ(report->cycle, 5u);
  EXPECT_NEAR(report->time.seconds, 0.005, 1e-12);
  EXPECT_TRUE(contains(report->message(), "hardware read() returned an error at t = 0.005 s (cycle 5)"))
      << report->message();
  EXPECT_FALSE(loop.takeHardwareErrorReport().has_value());  // once

  // A new episode after clean cycles is reported again.
  f.hw.write_script.from = 35;
  f.hw.write_script.until = 36;
  loop.runFor(Duration(0.01));
  EXPECT_EQ(loop.statistics().snapshot().hardware_errors, 11u);
  const auto second = loop.takeHardwareErrorReport();
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->call, HardwareCall::write);
  EXPECT_EQ(second->cycle, 35u);
  EXPECT_FALSE(loop.logHardwareErrorReport());
}

TEST(SimulationLoop, CycleOnceReportsTheWorstHardwareResult) {
  LoopFixture f(0.001);
  f.hw.step_script.from = 1;
  f.hw.step_script.until = 2;
  SimulationLoop loop(f.hw, f.manager);
  EXPECT_EQ(loop.cycleOnce(), ReturnType::ok);
  EXPECT_EQ(loop.cycleOnce(), ReturnType::error);
  EXPECT_EQ(loop.cycleOnce(), ReturnType::ok);
  EXPECT_TRUE(loop.logHardwareErrorReport());  // logs the step() error ...
  EXPECT_FALSE(loop.takeHardwareErrorReport().has_value());  // ... once
  EXPECT_EQ(loop.statistics().snapshot().hardware_errors, 1u);
}

TEST(SimulationLoop, StopsAfterTheConfiguredNumberOfFailedCyclesInARow) {
  LoopFixture f(0.001);
  f.hw.read_script.from = 5;  // every read from 5 on fails
  SimulationLoop::Options options;
  options.stop_after_failed_cycles = 3;
  SimulationLoop loop(f.hw, f.manager, options);
  std::atomic<bool> never{false};
  loop.run(never);  // returns by itself
  EXPECT_EQ(f.hw.steps, 8u);  // cycles 5, 6, 7 failed
  EXPECT_TRUE(loop.hardwareAskedToStop());
  EXPECT_EQ(loop.statistics().snapshot().hardware_errors, 3u);
  loop.runFor(Duration(1.0));  // refuses to run on
  EXPECT_EQ(f.hw.steps, 8u);
  loop.clearHardwareStop();
  loop.runFor(Duration(0.001));
  EXPECT_EQ(f.hw.steps, 9u);
}

TEST(SimulationLoop, HardwareDeactivateStopsTheLoopCleanly) {
  LoopFixture f(0.001);
  f.hw.step_script.from = 9;
  f.hw.step_script.until = 10;
  f.hw.step_script.result = ReturnType::deactivate;
  SimulationLoop loop(f.hw, f.manager);
  std::atomic<bool> never{false};
  loop.run(never);
  EXPECT_EQ(f.hw.steps, 10u);
  EXPECT_TRUE(loop.hardwareAskedToStop());
  EXPECT_EQ(loop.statistics().snapshot().hardware_errors, 0u);
  EXPECT_FALSE(loop.takeHardwareErrorReport().has_value());
}

TEST(SimulationLoop, SetsTheTopicBusClockToSimulatedTime) {
  LoopFixture f(0.001);
  realtime::TopicBus bus;
  SimulationLoop::Options options;
  options.topic_bus = &bus;
  SimulationLoop loop(f.hw, f.manager, options);
  loop.runFor(Duration(0.25));
  // The clock holds the time of the last cycle (its state was read at 0.249 s).
  EXPECT_NEAR(bus.now().seconds, 0.249, 1e-12);
}

}  // namespace
}  // namespace servoloop::controller_manager
