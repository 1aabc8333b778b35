#include "alloc_counter.hpp"

#include <execinfo.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <new>

namespace {
std::atomic<int> g_active_all{0};
thread_local int t_active = 0;
std::atomic<int> g_any{0};
std::atomic<std::size_t> g_allocations{0};
std::atomic<std::size_t> g_deallocations{0};

// The stack of the first counted allocation (written by the thread that made it).
constexpr int kMaxFrames = 48;
void* g_first_stack[kMaxFrames];
std::atomic<int> g_first_stack_depth{0};
thread_local bool t_in_backtrace = false;

void* counted_alloc(std::size_t size, std::size_t alignment) {
  if (g_any.load(std::memory_order_relaxed) > 0 &&
      (t_active > 0 || g_active_all.load(std::memory_order_relaxed) > 0)) {
    if (g_allocations.fetch_add(1, std::memory_order_relaxed) == 0 && !t_in_backtrace) {
      t_in_backtrace = true;  // backtrace() itself must not be counted or recurse
      g_first_stack_depth.store(backtrace(g_first_stack, kMaxFrames), std::memory_order_release);
      t_in_backtrace = false;
    }
  }
  if (size == 0) size = 1;
  void* p = nullptr;
  if (alignment > alignof(std::max_align_t)) {
    if (posix_memalign(&p, alignment, size) != 0) p = nullptr;
  } else {
    p = std::malloc(size);
  }
  return p;
}

void counted_free(void* p) {
  if (p == nullptr) return;
  if (g_any.load(std::memory_order_relaxed) > 0 &&
      (t_active > 0 || g_active_all.load(std::memory_order_relaxed) > 0)) {
    g_deallocations.fetch_add(1, std::memory_order_relaxed);
  }
  std::free(p);
}
}  // namespace

namespace servoloop::testing {
AllocationCounter::AllocationCounter(Scope scope) : scope_(scope) {
  // backtrace() loads its unwinder (and allocates) on first use: do that now,
  // before anything is counted.
  void* warm_up[2];
  backtrace(warm_up, 2);
  reset();
  if (scope_ == Scope::all_threads) {
    g_active_all.fetch_add(1);
  } else {
    ++t_active;
  }
  g_any.fetch_add(1);
}
AllocationCounter::~AllocationCounter() {
  g_any.fetch_sub(1);
  if (scope_ == Scope::all_threads) {
    g_active_all.fetch_sub(1);
  } else {
    --t_active;
  }
}
std::size_t AllocationCounter::allocations() const { return g_allocations.load(); }
std::size_t AllocationCounter::deallocations() const { return g_deallocations.load(); }
void AllocationCounter::reset() {
  g_allocations.store(0);
  g_deallocations.store(0);
  g_first_stack_depth.store(0);
}

void AllocationCounter::printFirstCountedStack(int fd) {
  const int depth = g_first_stack_depth.load(std::memory_order_acquire);
  const char* header = depth > 0 ? "stack of the first counted allocation:\n"
                                 : "no counted allocation recorded a stack\n";
  if (write(fd, header, std::strlen(header)) < 0) return;
  if (depth > 0) backtrace_symbols_fd(g_first_stack, depth, fd);
}
}  // namespace servoloop::testing

void* operator new(std::size_t size) {
  void* p = counted_alloc(size, 0);
  if (!p) throw std::bad_alloc();
  return p;
}
void* operator new[](std::size_t size) {
  void* p = counted_alloc(size, 0);
  if (!p) throw std::bad_alloc();
  return p;
}
void* operator new(std::size_t size, std::align_val_t al) {
  void* p = counted_alloc(size, static_cast<std::size_t>(al));
  if (!p) throw std::bad_alloc();
  return p;
}
void* operator new[](std::size_t size, std::align_val_t al) {
  void* p = counted_alloc(size, static_cast<std::size_t>(al));
  if (!p) throw std::bad_alloc();
  return p;
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return counted_alloc(size, 0); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return counted_alloc(size, 0); }
void operator delete(void* p) noexcept { counted_free(p); }
void operator delete[](void* p) noexcept { counted_free(p); }
void operator delete(void* p, std::size_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::size_t) noexcept { counted_free(p); }
void operator delete(void* p, std::align_val_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { counted_free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { counted_free(p); }
