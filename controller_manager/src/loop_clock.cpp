// Monotonic time and absolute sleeps for the control loops.
#include "servoloop/controller_manager/loop_clock.hpp"

#include <atomic>
#include <cerrno>
#include <ctime>
#include <fstream>
#include <string>

#if defined(__x86_64__)
#include <x86intrin.h>
#endif

namespace servoloop::controller_manager::loop_clock {

namespace {
constexpr std::int64_t kNsPerSecond = 1'000'000'000;
}

std::int64_t nowNs() noexcept {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<std::int64_t>(now.tv_sec) * kNsPerSecond + now.tv_nsec;
}

namespace {

// The scaling of the time-stamp counter: ns = base_ns + (tsc − base_tsc) · ns_per_tick.
struct TscScale {
  bool use_tsc = false;
  std::uint64_t base_tsc = 0;
  std::int64_t base_ns = 0;
  double ns_per_tick = 0.0;
};

TscScale g_tsc_scale;                    // written once, before g_tsc_ready is set
std::atomic<bool> g_tsc_ready{false};

#if defined(__x86_64__)
// The kernel keeps CLOCK_MONOTONIC with the TSC only when the counter is
// invariant and synchronised across cores; then it is safe for us too.
bool kernelClocksourceIsTsc() {
  std::ifstream file("/sys/devices/system/clocksource/clocksource0/current_clocksource");
  std::string name;
  return static_cast<bool>(file >> name) && name == "tsc";
}

TscScale calibrate() {
  TscScale scale;
  if (!kernelClocksourceIsTsc()) return scale;
  // 0.5 ms: the two clock reads' jitter (tens of ns) is then 1e-4 of the
  // interval, far below what a cycle's duration or a run's wall time shows.
  constexpr std::int64_t kCalibrationNs = 500'000;
  const std::int64_t start_ns = nowNs();
  const std::uint64_t start_tsc = __rdtsc();
  std::int64_t end_ns = start_ns;
  while (end_ns - start_ns < kCalibrationNs) end_ns = nowNs();
  const std::uint64_t end_tsc = __rdtsc();
  if (end_tsc <= start_tsc) return scale;
  scale.use_tsc = true;
  scale.base_tsc = end_tsc;
  scale.base_ns = end_ns;
  scale.ns_per_tick = static_cast<double>(end_ns - start_ns) / static_cast<double>(end_tsc - start_tsc);
  return scale;
}
#else
TscScale calibrate() { return TscScale{}; }
#endif

}  // namespace

bool prepareCycleClock() {
  static const bool uses_tsc = [] {
    g_tsc_scale = calibrate();
    g_tsc_ready.store(true, std::memory_order_release);
    return g_tsc_scale.use_tsc;
  }();
  return uses_tsc;
}

std::int64_t cycleClockNs() noexcept {
#if defined(__x86_64__)
  if (g_tsc_ready.load(std::memory_order_acquire) && g_tsc_scale.use_tsc) {
    const auto ticks = static_cast<std::int64_t>(__rdtsc() - g_tsc_scale.base_tsc);
    return g_tsc_scale.base_ns + static_cast<std::int64_t>(static_cast<double>(ticks) * g_tsc_scale.ns_per_tick);
  }
#endif
  return nowNs();
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
