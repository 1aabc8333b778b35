#pragma once
// Hands whole objects from a non-real-time thread to the real-time thread and
// back for deletion, so the real-time thread neither allocates nor frees:
//   - the non-real-time side builds an object and push()es it (a newer push
//     replaces one the real-time side has not taken yet, and hands that one
//     back to its caller);
//   - the real-time side take()s the newest, uses it as long as it likes and
//     retire()s it when done;
//   - the non-real-time side deletes retired objects at its next push() or
//     collect(), and everything left when the handoff is destroyed.
// One pushing thread and one real-time thread. Lock-free; take() and
// retire() never block, allocate or free.
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>

namespace servoloop::realtime {

template <class T, std::size_t kRetireSlots = 8>
class RealtimeHandoff {
 public:
  RealtimeHandoff() = default;
  RealtimeHandoff(const RealtimeHandoff&) = delete;
  RealtimeHandoff& operator=(const RealtimeHandoff&) = delete;
  // Non-real-time, with the real-time side no longer using the handoff.
  ~RealtimeHandoff() {
    delete incoming_.exchange(nullptr, std::memory_order_acquire);
    collect();
  }

  // Non-real-time. Deletes what was retired, then offers item. Returns the
  // item this one replaced if the real-time side never took it (else null).
  std::unique_ptr<T> push(std::unique_ptr<T> item) {
    collect();
    return std::unique_ptr<T>(incoming_.exchange(item.release(), std::memory_order_acq_rel));
  }

  // Non-real-time. Deletes what the real-time side retired.
  void collect() {
    std::size_t tail = tail_.load(std::memory_order_relaxed);
    const std::size_t head = head_.load(std::memory_order_acquire);
    while (tail != head) {
      delete slots_[tail % kRetireSlots];
      slots_[tail % kRetireSlots] = nullptr;
      ++tail;
    }
    tail_.store(tail, std::memory_order_release);
  }

  // Real-time: the newest pushed item, now owned by the caller, or null.
  T* take() noexcept { return incoming_.exchange(nullptr, std::memory_order_acq_rel); }

  // Real-time: gives an item taken earlier back for deletion. With every
  // slot full (the pushing side has not collected for kRetireSlots
  // retirements) the item is kept forever instead and counted.
  void retire(T* item) noexcept {
    if (item == nullptr) return;
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_.load(std::memory_order_acquire) >= kRetireSlots) {
      leaked_.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    slots_[head % kRetireSlots] = item;
    head_.store(head + 1, std::memory_order_release);
  }

  // Items retire() could not give back (any thread).
  std::uint64_t leaked() const noexcept { return leaked_.load(std::memory_order_relaxed); }

 private:
  std::atomic<T*> incoming_{nullptr};
  std::array<T*, kRetireSlots> slots_{};
  std::atomic<std::size_t> head_{0};  // written by the real-time side
  std::atomic<std::size_t> tail_{0};  // written by the pushing side
  std::atomic<std::uint64_t> leaked_{0};
};

}  // namespace servoloop::realtime
