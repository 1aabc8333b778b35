#pragma once
// How a control loop tells the non-real-time side that the hardware failed,
// without logging on the real-time thread: the real-time thread records each
// read/write/step result; the first error of an episode (a run of cycles in
// which some hardware call failed) leaves one report behind a lock-free flag,
// which the non-real-time side takes — so a failure that persists for
// thousands of cycles is reported once, not once per cycle. Every error is
// still counted (LoopStatistics::hardware_errors).
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "servoloop/core/return_type.hpp"
#include "servoloop/core/time.hpp"

namespace servoloop::controller_manager {

enum class HardwareCall : std::uint8_t { read, write, step };

// "read", "write", "step".
const char* toString(HardwareCall call) noexcept;

// A joint state that read() left not finite (NaN or infinite): the loop
// counts such a read() as failed (ReturnType::error), whatever it returned.
struct NonFiniteJointState {
  const std::string* joint = nullptr;  // the joint's name (owned by the loop)
  const char* quantity = "position";   // "position", "velocity" or "effort"
  double value = 0.0;
};

struct HardwareErrorReport {
  // The longest joint name a report carries (longer ones are cut).
  static constexpr std::size_t kJointNameCapacity = 128;

  HardwareCall call = HardwareCall::read;  // the first call that failed in the episode
  Time time;                               // control time of the cycle it failed in
  std::uint64_t cycle = 0;                 // loop cycle it failed in (0-based)
  // When the call returned ok but left a joint state not finite: what
  // (quantity is null otherwise). Copied, so the report outlives the loop.
  const char* quantity = nullptr;  // static text: "position", "velocity", "effort"
  double value = 0.0;
  std::array<char, kJointNameCapacity> joint{};  // NUL-terminated

  // "hardware read() returned an error at t = 1.234 s (cycle 1234)", or
  // "hardware read() gave joint 'joint1' a position of nan at t = 0.02 s
  // (cycle 20)".
  std::string message() const;
};

class LoopHardwareErrors {
 public:
  // Real-time. Records one hardware call's result; returns true when it was an
  // error (the caller counts it).
  // non_finite (may be null): the joint state that made an ok call an error.
  bool record(HardwareCall call, ReturnType result, Time time, std::uint64_t cycle,
              const NonFiniteJointState* non_finite = nullptr) noexcept;

  // Real-time. Closes a cycle: true if a call failed in it. A clean cycle ends
  // the episode, so the next error is reported again.
  bool endCycle() noexcept;

  // Real-time safe. Cycles in a row, up to the last endCycle(), in which a hardware call failed.
  std::uint64_t consecutiveFailedCycles() const noexcept {
    return consecutive_failed_cycles_.load(std::memory_order_relaxed);
  }

  // Non-real-time (any one thread). The waiting report, once; nullopt when
  // there is none. While a report waits, later episodes are counted but
  // leave no report of their own.
  std::optional<HardwareErrorReport> takeReport() noexcept;

 private:
  // Written by the real-time thread only while pending_ is false.
  HardwareErrorReport report_;
  std::atomic<bool> pending_{false};
  bool failed_this_cycle_ = false;  // real-time thread only
  bool in_episode_ = false;         // real-time thread only
  std::atomic<std::uint64_t> consecutive_failed_cycles_{0};
};

}  // namespace servoloop::controller_manager
