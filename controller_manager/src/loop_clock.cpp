// Monotonic time and absolute sleeps for the control loops.
#include "servoloop/controller_manager/loop_clock.hpp"

#include <cerrno>
#include <ctime>

namespace servoloop::controller_manager::loop_clock {

namespace {
constexpr std::int64_t kNsPerSecond = 1'000'000'000;
}

std::int64_t nowNs() noexcept {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<std::int64_t>(now.tv_sec) * kNsPerSecond + now.tv_nsec;
}

void sleepUntilNs(std::int64_t deadline_ns) noexcept {
  timespec deadline{};
  deadline.tv_sec = static_cast<time_t>(deadline_ns / kNsPerSecond);
  deadline.tv_nsec = static_cast<long>(deadline_ns % kNsPerSecond);
  // An absolute deadline needs no recomputation when a signal interrupts it.
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &deadline, nullptr) == EINTR) {
  }
}

}  // namespace servoloop::controller_manager::loop_clock
