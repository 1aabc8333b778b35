#pragma once
// Counts Bullet's own allocations: Bullet allocates through btAlignedAlloc
// (malloc underneath), which the operator-new counter (alloc_counter.hpp)
// does not see. Including this header installs a counting hook before main,
// so before any Bullet object exists and every block is freed by the
// allocator that made it. Needs Bullet's headers and LinearMath in double
// precision (BT_USE_DOUBLE_PRECISION).
//
//   bullet_alloc::all      every allocation since start (the hook works)
//   bullet_alloc::counted  those made while the allocating thread's
//                          bullet_alloc::counting is true (a real-time thread under test)
#include <atomic>
#include <cstddef>
#include <cstdlib>

#include <LinearMath/btAlignedAllocator.h>

namespace servoloop::testing::bullet_alloc {

inline std::atomic<std::size_t> all{0};
inline std::atomic<std::size_t> counted{0};
inline thread_local bool counting = false;

inline void* countingAlloc(std::size_t size) {
  all.fetch_add(1, std::memory_order_relaxed);
  if (counting) counted.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size);
}
inline void release(void* p) { std::free(p); }

inline const bool kInstalled = [] {
  btAlignedAllocSetCustom(countingAlloc, release);
  return true;
}();

}  // namespace servoloop::testing::bullet_alloc
