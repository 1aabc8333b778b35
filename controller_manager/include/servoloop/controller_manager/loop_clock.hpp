#pragma once
// The monotonic clock the control loops pace themselves with, in integer
// nanoseconds so absolute deadlines never accumulate rounding drift.
// Everything here is real-time safe: no allocation, no locks.
#include <cstdint>

namespace servoloop::controller_manager::loop_clock {

// Nanoseconds of CLOCK_MONOTONIC (arbitrary origin, never jumps).
std::int64_t nowNs() noexcept;

// A cheaper clock for timing cycles that do not sleep (a free-running
// simulation loop): the CPU's time-stamp counter scaled to nanoseconds, where
// the kernel itself keeps time with it (x86-64, clocksource "tsc": an
// invariant counter); CLOCK_MONOTONIC everywhere else. Calibrated against
// CLOCK_MONOTONIC once per process (about 2 ms, in the first call of
// prepareCycleClock(); call that outside the real-time path), after which it
// reads like nowNs() (same origin, drift within the calibration's accuracy).
// Use differences of cycleClockNs() readings; do not sleep until them.
std::int64_t cycleClockNs() noexcept;
// Non-real-time. Calibrates the cycle clock if not done yet (it may read a
// file and allocate). Returns true when it reads the time-stamp counter.
bool prepareCycleClock();

// Sleeps until the monotonic clock reaches deadline_ns (clock_nanosleep with
// TIMER_ABSTIME, resumed after signals). Returns at once if it has passed.
void sleepUntilNs(std::int64_t deadline_ns) noexcept;

}  // namespace servoloop::controller_manager::loop_clock
