// The simulation loop's real-time thread allocates nothing: 100,000 cycles
// with a running controller, a cycle hook and the topic bus clock, after
// start-up.
#include <gtest/gtest.h>

#include "alloc_counter.hpp"
#include "control_loop_test_support.hpp"
#include "servoloop/controller_manager/safety_supervisor.hpp"
#include "servoloop/controller_manager/simulation_loop.hpp"
#include "servoloop/controller_manager/wall_clock_loop.hpp"
#include "servoloop/realtime/topic_bus.hpp"

namespace servoloop::controller_manager {
namespace {

using servoloop::testing::AllocationCounter;

TEST(ControlLoopAllocation, HundredThousandSimulationCyclesAllocateNothing) {
  constexpr std::uint64_t kCycles = 100000;
  testing::LoopFixture f(0.001, 500.0);  // k = 2: steps with and without an update
  f.recorder->enabled = false;
  realtime::TopicBus bus;
  testing::RecordingHook hook(f.recorder);
  SimulationLoop::Options options;
  options.cycle_hook = &hook;
  options.topic_bus = &bus;
  SimulationLoop loop(f.hw, f.manager, options);
  f.requestStart();
  loop.cycleOnce();  // start-up: carries out the switch
  ASSERT_TRUE(f.controller()->isRunning());
  // Hardware errors take the reporting path too.
  f.hw.read_script.from = 1000;
  f.hw.read_script.until = 1010;

  std::size_t allocations = 0;
  {
    AllocationCounter counter;  // this (the loop's) thread only
    loop.runFor(Duration(static_cast<double>(kCycles) * 0.001));
    allocations = counter.allocations();
  }
  EXPECT_EQ(allocations, 0u);
  EXPECT_EQ(loop.stepsTaken(), kCycles + 1);
  EXPECT_EQ(f.controller()->updates, kCycles / 2);
  EXPECT_EQ(loop.statistics().snapshot().hardware_errors, 10u);
  EXPECT_TRUE(f.controller()->isRunning());
}

// A simulation loop at 1 kHz with a safety supervisor, its controller
// started (the switch carried out by one cycle).
struct SafeSimulation {
  SafeSimulation() : loop(f.hw, f.manager, optionsWith(&safety)) {
    f.recorder->enabled = false;
    f.requestStart();
    loop.cycleOnce();
  }
  static SimulationLoop::Options optionsWith(SafetySupervisor* safety) {
    SimulationLoop::Options options;
    options.safety = safety;
    return options;
  }
  testing::LoopFixture f{0.001, 500.0};
  SafetySupervisor safety{f.hw};
  SimulationLoop loop;
};

// With the safety layer: an emergency stop engaged and released every 1000
// cycles, the hardware input polled every cycle, and a read error's
// protective stop containing the controller, all allocation-free.
TEST(ControlLoopAllocation, SafetyTransitionsAllocateNothing) {
  constexpr std::uint64_t kChunks = 50;
  constexpr std::uint64_t kCyclesPerChunk = 1000;
  SafeSimulation s;
  ASSERT_TRUE(s.f.controller()->isRunning());
  auto& [f, safety, loop] = s;
  f.hw.read_script.from = 40000;
  f.hw.read_script.until = 40001;

  std::size_t allocations = 0;
  {
    AllocationCounter counter;  // this (the loop's) thread only
    for (std::uint64_t chunk = 0; chunk < kChunks; ++chunk) {
      if (chunk % 2 == 0) {
        safety.engageEmergencyStop(EmergencyStopSource::command);
      } else {
        safety.releaseEmergencyStop(nullptr);
      }
      loop.runFor(Duration(static_cast<double>(kCyclesPerChunk) * 0.001));
    }
    allocations = counter.allocations();
  }
  EXPECT_EQ(allocations, 0u);
  EXPECT_EQ(safety.emergencyStops(), kChunks / 2);
  EXPECT_EQ(safety.protectiveStops(), 1u);
  EXPECT_EQ(f.controller()->state(), ControllerState::failed);
}

// The check of every joint state after read(), clean and finding a NaN
// (reported naming the joint, a protective stop containing the controller),
// allocates nothing either.
TEST(ControlLoopAllocation, NonFiniteJointStateChecksAllocateNothing) {
  constexpr std::uint64_t kCycles = 20000;
  SafeSimulation s;
  ASSERT_TRUE(s.f.controller()->isRunning());
  auto& [f, safety, loop] = s;
  f.hw.nan_position_from = 10000;  // reads 10000..10004
  f.hw.nan_position_until = 10005;

  std::size_t allocations = 0;
  {
    AllocationCounter counter;  // this (the loop's) thread only
    loop.runFor(Duration(static_cast<double>(kCycles) * 0.001));
    allocations = counter.allocations();
  }
  EXPECT_EQ(allocations, 0u);
  EXPECT_EQ(loop.stepsTaken(), kCycles + 1);
  EXPECT_EQ(loop.statistics().snapshot().hardware_errors, 5u);
  EXPECT_EQ(safety.protectiveStops(), 1u);
  EXPECT_EQ(f.controller()->state(), ControllerState::failed);
  const auto report = loop.takeHardwareErrorReport();
  ASSERT_TRUE(report.has_value());
  EXPECT_NE(report->message().find("read() gave joint 'joint1' a position of nan"), std::string::npos)
      << report->message();
}

// The wall-clock loop with its per-phase statistics (read, the controller's
// update, write, wake-up latency, period jitter), a statistics reset asked
// for mid-run, and the safety layer: 2000 cycles at 10 kHz, no allocation.
TEST(ControlLoopAllocation, WallClockCyclesWithStatisticsAndAResetAllocateNothing) {
  testing::LoopFixture f(0.0001, 10000.0);
  f.recorder->enabled = false;
  SafetySupervisor safety(f.hw);
  WallClockLoop::Options options;
  options.safety = &safety;
  options.step_simulation = true;
  WallClockLoop loop(f.hw, f.manager, options);
  f.requestStart();
  loop.runFor(Duration(0.001));  // start-up: carries out the switch
  ASSERT_TRUE(f.controller()->isRunning());

  std::size_t allocations = 0;
  {
    AllocationCounter counter;
    loop.runFor(Duration(0.1));
    loop.requestStatisticsReset();
    loop.runFor(Duration(0.1));
    allocations = counter.allocations();
  }
  EXPECT_EQ(allocations, 0u);
  const LoopStatisticsSnapshot s = loop.statistics().snapshot();
  EXPECT_GT(s.read.count, 0u);
  EXPECT_LE(s.cycles, 1001u);  // counted since the reset only
  EXPECT_GT(f.manager.updateTimes()[0].second.count, 0u);
}

}  // namespace
}  // namespace servoloop::controller_manager
