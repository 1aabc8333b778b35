// Asymmetric fences through membarrier(2) (asymmetric_fence.hpp).
#include "asymmetric_fence.hpp"

#include <linux/membarrier.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace servoloop::controller_manager::asymmetric_fence {

namespace {

long membarrier(int command) noexcept { return syscall(__NR_membarrier, command, 0, 0); }

// ThreadSanitizer cannot see the fence membarrier(2) runs on other threads, so
// it would report the light side's plain ordering as a race: under it both
// sides use the seq_cst fallback, which it understands.
#if defined(__SANITIZE_THREAD__)
#define SERVOLOOP_UNDER_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define SERVOLOOP_UNDER_TSAN 1
#endif
#endif
#ifndef SERVOLOOP_UNDER_TSAN
#define SERVOLOOP_UNDER_TSAN 0
#endif
constexpr bool kThreadSanitizer = SERVOLOOP_UNDER_TSAN != 0;

bool registerProcess() noexcept {
  if (kThreadSanitizer) return false;
  const long commands = membarrier(MEMBARRIER_CMD_QUERY);
  if (commands < 0 || (commands & MEMBARRIER_CMD_PRIVATE_EXPEDITED) == 0) return false;
  return membarrier(MEMBARRIER_CMD_REGISTER_PRIVATE_EXPEDITED) == 0;
}

}  // namespace

bool available() noexcept {
  static const bool registered = registerProcess();
  return registered;
}

namespace {
// Registered while the library loads, when a program usually has one thread:
// the kernel then needs no RCU grace period (about 10 ms of waiting once the
// process has threads) to register it.
[[maybe_unused]] const bool g_registered_at_load = available();
}  // namespace

void heavy() noexcept {
  if (available() && membarrier(MEMBARRIER_CMD_PRIVATE_EXPEDITED) == 0) return;
#if !SERVOLOOP_UNDER_TSAN
  // (Under TSan available() is false and callers use seq_cst operations on
  // both sides instead of this pair; TSan does not model fences.)
  std::atomic_thread_fence(std::memory_order_seq_cst);
#endif
}

}  // namespace servoloop::controller_manager::asymmetric_fence
