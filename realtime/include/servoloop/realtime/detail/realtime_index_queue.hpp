#pragma once
// A bounded lock-free FIFO of small integers (slot indices), safe for any
// number of pushing and popping threads (Vyukov's bounded MPMC queue design:
// each cell carries a sequence number that says whose turn it is).
//
// Memory is reserved in the constructor; push() and pop() never allocate,
// never block, and fail instead of waiting when the queue is full or empty.
// A push that completes happens-before the pop that returns its value, so a
// slot index passed through the queue hands over the slot's contents too.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>

namespace servoloop::realtime {

class RealtimeIndexQueue {
 public:
  // Room for at least min_capacity values (rounded up to a power of two).
  explicit RealtimeIndexQueue(std::size_t min_capacity) {
    std::size_t capacity = 2;
    while (capacity < min_capacity) capacity *= 2;
    mask_ = capacity - 1;
    cells_ = std::make_unique<Cell[]>(capacity);
    for (std::size_t i = 0; i < capacity; ++i) cells_[i].sequence.store(i, std::memory_order_relaxed);
  }
  RealtimeIndexQueue(const RealtimeIndexQueue&) = delete;
  RealtimeIndexQueue& operator=(const RealtimeIndexQueue&) = delete;

  std::size_t capacity() const noexcept { return mask_ + 1; }

  // Any thread, a hint: false when nothing was pushed that is not popped yet
  // (a push racing with this call may or may not be seen).
  bool mayHoldValues() const noexcept {
    return head_.load(std::memory_order_acquire) != tail_.load(std::memory_order_acquire);
  }

  // Real-time safe. False when full.
  bool push(std::uint32_t value) noexcept {
    std::size_t position = tail_.load(std::memory_order_relaxed);
    for (;;) {
      Cell& cell = cells_[position & mask_];
      const std::size_t sequence = cell.sequence.load(std::memory_order_acquire);
      const auto lag = static_cast<std::ptrdiff_t>(sequence) - static_cast<std::ptrdiff_t>(position);
      if (lag == 0) {
        if (tail_.compare_exchange_weak(position, position + 1, std::memory_order_relaxed)) {
          cell.value = value;
          cell.sequence.store(position + 1, std::memory_order_release);
          return true;
        }
      } else if (lag < 0) {
        return false;  // the cell still holds a value from one lap ago: full
      } else {
        position = tail_.load(std::memory_order_relaxed);
      }
    }
  }

  // Real-time safe. False when empty.
  bool pop(std::uint32_t& value) noexcept {
    std::size_t position = head_.load(std::memory_order_relaxed);
    for (;;) {
      Cell& cell = cells_[position & mask_];
      const std::size_t sequence = cell.sequence.load(std::memory_order_acquire);
      const auto lag = static_cast<std::ptrdiff_t>(sequence) - static_cast<std::ptrdiff_t>(position + 1);
      if (lag == 0) {
        if (head_.compare_exchange_weak(position, position + 1, std::memory_order_relaxed)) {
          value = cell.value;
          cell.sequence.store(position + mask_ + 1, std::memory_order_release);
          return true;
        }
      } else if (lag < 0) {
        return false;  // nothing pushed into this cell yet: empty
      } else {
        position = head_.load(std::memory_order_relaxed);
      }
    }
  }

 private:
  struct Cell {
    std::atomic<std::size_t> sequence{0};
    std::uint32_t value = 0;
  };

  std::unique_ptr<Cell[]> cells_;
  std::size_t mask_ = 0;
  alignas(64) std::atomic<std::size_t> tail_{0};  // next position to push
  alignas(64) std::atomic<std::size_t> head_{0};  // next position to pop
};

}  // namespace servoloop::realtime
