#pragma once
// Waiting for a condition instead of sleeping for a fixed time: polls
// `condition` every `poll` until it holds or `timeout` has passed. The timeout
// is an upper bound for a loaded machine, never the expected duration.
#include <chrono>
#include <thread>

namespace servoloop::testing {

template <class Condition>
bool waitUntil(Condition&& condition, std::chrono::duration<double> timeout,
               std::chrono::milliseconds poll = std::chrono::milliseconds(5)) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(timeout);
  while (true) {
    if (condition()) return true;
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(poll);
  }
}

}  // namespace servoloop::testing
