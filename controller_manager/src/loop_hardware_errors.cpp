// LoopHardwareErrors: one report per episode of hardware failures, handed to
// the non-real-time side through a single atomic flag.
#include "servoloop/controller_manager/loop_hardware_errors.hpp"

#include <algorithm>
#include <cstring>

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
  if (quantity != nullptr) {
    return fmt::format("hardware {}() gave joint '{}' a {} of {} at t = {:.6g} s (cycle {}); a joint state must be a "
                       "finite number, so the read counts as failed",
                       toString(call), joint.data(), quantity, value, time.seconds, cycle);
  }
  return fmt::format("hardware {}() returned an error at t = {:.6g} s (cycle {})", toString(call),
                     time.seconds, cycle);
}

bool LoopHardwareErrors::record(HardwareCall call, ReturnType result, Time time, std::uint64_t cycle,
                                const NonFiniteJointState* non_finite) noexcept {
  if (result != ReturnType::error) return false;
  failed_this_cycle_ = true;
  if (!in_episode_) {
    in_episode_ = true;
    // The reader owns report_ while pending_ is set; leave it alone then.
    if (!pending_.load(std::memory_order_acquire)) {
      report_.call = call;
      report_.time = time;
      report_.cycle = cycle;
      report_.quantity = nullptr;
      report_.joint[0] = '\0';
      if (non_finite != nullptr) {
        report_.quantity = non_finite->quantity;
        report_.value = non_finite->value;
        if (non_finite->joint != nullptr) {
          // Copied (no allocation), cut to the capacity.
          const std::size_t length = std::min(non_finite->joint->size(), report_.joint.size() - 1);
          std::memcpy(report_.joint.data(), non_finite->joint->data(), length);
          report_.joint[length] = '\0';
        }
      }
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
