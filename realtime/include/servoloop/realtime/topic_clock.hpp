#pragma once
// The time the topic bus stamps messages with: the control loop's time once
// the loop sets it (simulated time in simulation), wall time since the bus
// was made before that. Real-time safe: both calls are lock-free.
#include <atomic>
#include <chrono>

#include "servoloop/core/time.hpp"

namespace servoloop::realtime {

class TopicClock {
 public:
  TopicClock() : start_(std::chrono::steady_clock::now()) {}

  // Real-time: the control loop calls this every cycle.
  void set(Time now) noexcept {
    seconds_.store(now.seconds, std::memory_order_relaxed);
    is_set_.store(true, std::memory_order_release);
  }

  // Real-time: the last time set(), or steady time since construction if never set.
  Time now() const noexcept {
    if (is_set_.load(std::memory_order_acquire)) return Time(seconds_.load(std::memory_order_relaxed));
    return Time(std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
  }

 private:
  std::chrono::steady_clock::time_point start_;
  std::atomic<double> seconds_{0.0};
  std::atomic<bool> is_set_{false};
};

}  // namespace servoloop::realtime
