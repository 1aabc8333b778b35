#pragma once
// The monotonic clock the control loops pace themselves with, in integer
// nanoseconds so absolute deadlines never accumulate rounding drift.
// Everything here is real-time safe: no allocation, no locks.
#include <cstdint>

namespace servoloop::controller_manager::loop_clock {

// Nanoseconds of CLOCK_MONOTONIC (arbitrary origin, never jumps).
std::int64_t nowNs() noexcept;

// Sleeps until the monotonic clock reaches deadline_ns (clock_nanosleep with
// TIMER_ABSTIME, resumed after signals). Returns at once if it has passed.
void sleepUntilNs(std::int64_t deadline_ns) noexcept;

}  // namespace servoloop::controller_manager::loop_clock
