// LoopHardwareErrors: one report per episode of hardware failures, handed to
// the non-real-time side through a single atomic flag.
#include "servoloop/controller_manager/loop_hardware_errors.hpp"

#include <fmt/format.h>

namespace servoloop::controller_manager {

const char* toString(HardwareCall call) noexcept {
  switch (call) {
    case HardwareCall::read:
      return "read";
    case HardwareCall::write:
      return "write";
    case HardwareCall::step:
      return "step";
  }
  return "unknown";
}

std::string HardwareErrorReport::message() const {
  return fmt::format("hardware {}() returned an error at t = {:.6g} s (cycle {})", toString(call),
                     time.seconds, cycle);
}

bool LoopHardwareErrors::record(HardwareCall call, ReturnType result, Time time,
                                std::uint64_t cycle) noexcept {
  if (result != ReturnType::error) return false;
  failed_this_cycle_ = true;
  if (!in_episode_) {
    in_episode_ = true;
    // The reader owns report_ while pending_ is set; leave it alone then.
    if (!pending_.load(std::memory_order_acquire)) {
      report_ = HardwareErrorReport{call, time, cycle};
      pending_.store(true, std::memory_order_release);
    }
  }
  return true;
}

bool LoopHardwareErrors::endCycle() noexcept {
  const bool failed = failed_this_cycle_;
  failed_this_cycle_ = false;
  if (failed) {
    consecutive_failed_cycles_.store(consecutive_failed_cycles_.load(std::memory_order_relaxed) + 1,
                                     std::memory_order_relaxed);
  } else {
    in_episode_ = false;
    consecutive_failed_cycles_.store(0, std::memory_order_relaxed);
  }
  return failed;
}

std::optional<HardwareErrorReport> LoopHardwareErrors::takeReport() noexcept {
  if (!pending_.load(std::memory_order_acquire)) return std::nullopt;
  HardwareErrorReport report = report_;
  pending_.store(false, std::memory_order_release);
  return report;
}

}  // namespace servoloop::controller_manager
