// The loops' clocks: the cycle clock (time-stamp counter where the kernel
// trusts it) against CLOCK_MONOTONIC, which the kernel keeps independently.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <thread>

#include "servoloop/controller_manager/loop_clock.hpp"

namespace servoloop::controller_manager {
namespace {

// When this program started: the cycle clock is calibrated once per process,
// by whichever test builds a loop first, at the latest here.
const std::int64_t g_program_start_ns = loop_clock::nowNs();

TEST(LoopClock, CycleClockReadsLikeTheMonotonicClock) {
  const bool uses_tsc = loop_clock::prepareCycleClock();
  // Same origin: a reading of each, taken back to back, agree within a
  // millisecond plus the scale's error since the calibration (its 2 ms window
  // read with about a microsecond of jitter: better than 1e-3; a slow
  // sanitizer build runs seconds between the calibration and this test).
  const std::int64_t cycle = loop_clock::cycleClockNs();
  const std::int64_t mono = loop_clock::nowNs();
  const std::int64_t since_calibration_ns = mono - g_program_start_ns;
  EXPECT_LT(std::llabs(mono - cycle), 1'000'000 + since_calibration_ns / 1000)
      << "time-stamp counter used: " << uses_tsc << ", " << since_calibration_ns << " ns since the program started";
}

TEST(LoopClock, CycleClockMeasuresAnIntervalAsTheMonotonicClockDoes) {
  loop_clock::prepareCycleClock();
  const std::int64_t cycle_before = loop_clock::cycleClockNs();
  const std::int64_t mono_before = loop_clock::nowNs();
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const std::int64_t mono_after = loop_clock::nowNs();
  const std::int64_t cycle_after = loop_clock::cycleClockNs();
  const std::int64_t mono_interval = mono_after - mono_before;
  const std::int64_t cycle_interval = cycle_after - cycle_before;
  // The cycle interval encloses the monotonic one (read outside it), by the
  // cost of two reads; a scale error of 1 % would show as 0.5 ms here.
  EXPECT_GE(cycle_interval, mono_interval - 50'000);
  EXPECT_LE(cycle_interval, mono_interval + mono_interval / 100 + 50'000);
}

TEST(LoopClock, CycleClockNeverGoesBackwards) {
  loop_clock::prepareCycleClock();
  std::int64_t previous = loop_clock::cycleClockNs();
  for (int i = 0; i < 200'000; ++i) {
    const std::int64_t now = loop_clock::cycleClockNs();
    ASSERT_GE(now, previous) << "reading " << i;
    previous = now;
  }
}

}  // namespace
}  // namespace servoloop::controller_manager
