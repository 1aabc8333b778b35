#pragma once
// Counts heap allocations made through global operator new (and malloc-backed
// containers) while a guard is alive. Link servoloop_alloc_counter into a test
// executable to replace the global allocation functions.
//
//   servoloop::testing::AllocationCounter counter;   // starts counting
//   run_cycles();
//   EXPECT_EQ(counter.allocations(), 0u);
#include <cstddef>

namespace servoloop::testing {

class AllocationCounter {
 public:
  // this_thread: only allocations made on the thread that built the counter
  // (the real-time thread under test); all_threads: every thread's.
  enum class Scope { this_thread, all_threads };
  explicit AllocationCounter(Scope scope = Scope::this_thread);
  ~AllocationCounter();
  AllocationCounter(const AllocationCounter&) = delete;
  AllocationCounter& operator=(const AllocationCounter&) = delete;

  // Allocations (operator new of any form) seen since construction or reset().
  std::size_t allocations() const;
  // Deallocations seen since construction or reset().
  std::size_t deallocations() const;
  void reset();

  // Writes the call stack of the first allocation counted since construction
  // or reset() to file descriptor fd (standard error by default), as
  // backtrace_symbols_fd prints it, or a line saying there was none. For a
  // test that found allocations on a path that must have none: the stack names
  // the culprit. Does not allocate.
  static void printFirstCountedStack(int fd = 2);

 private:
  Scope scope_;
};

}  // namespace servoloop::testing
