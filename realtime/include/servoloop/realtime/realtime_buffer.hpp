#pragma once
// Hands the latest value from non-real-time writers to one real-time reader
// (a triple buffer): the reader never blocks and never allocates, writers
// serialise among themselves on a mutex and never wait for the reader.
//
// Three slots, each a full T pre-sized from a prototype: the writer fills its
// private back slot and swaps it into the shared middle slot with one atomic
// exchange; the reader swaps the middle slot with its private front slot when
// the exchange flagged it as new. Neither side ever touches a slot the other
// one holds, so values with vectors and strings are always seen complete.
#include <array>
#include <atomic>
#include <cstdint>
#include <mutex>

namespace servoloop::realtime {

template <class T>
class RealtimeBuffer {
 public:
  // prototype pre-sizes every slot (e.g. a vector of the expected length), so
  // neither copying in nor reading out needs to grow anything.
  explicit RealtimeBuffer(const T& prototype = T{}) {
    for (Slot& slot : slots_) slot.value = prototype;
  }
  RealtimeBuffer(const RealtimeBuffer&) = delete;
  RealtimeBuffer& operator=(const RealtimeBuffer&) = delete;

  // Non-real-time: publishes value as the latest. Concurrent writers wait for
  // each other; the reader is never waited for.
  void writeFromNonRT(const T& value) {
    std::lock_guard lock(write_mutex_);
    Slot& back = slots_[back_];
    back.value = value;  // may allocate if value outgrew the prototype: writer side only
    back.sequence = ++write_count_;
    const std::uint8_t previous = middle_.exchange(static_cast<std::uint8_t>(back_ | kFreshBit),
                                                   std::memory_order_acq_rel);
    back_ = previous & kIndexMask;
  }

  // Real-time, single reader: the newest value written, or nullptr if nothing
  // was written since construction or the last clearFromRT(). The pointer stays
  // valid (and unchanged) until the next call of readFromRT()/clearFromRT().
  const T* readFromRT() noexcept {
    takeFresh();
    const Slot& front = slots_[front_];
    return front.sequence > cleared_up_to_ ? &front.value : nullptr;
  }

  // Real-time: copies the newest value into out (no allocation when out is as
  // large as the value); false, out untouched, when there is none.
  bool readFromRT(T& out) {
    const T* latest = readFromRT();
    if (latest == nullptr) return false;
    out = *latest;
    return true;
  }

  // Real-time: whether a value was written since the reader last looked.
  bool newDataAvailable() const noexcept {
    return (middle_.load(std::memory_order_acquire) & kFreshBit) != 0;
  }

  // Real-time: forgets every value written so far (readFromRT() returns
  // nullptr until the next write), e.g. when a controller restarts.
  void clearFromRT() noexcept {
    takeFresh();
    cleared_up_to_ = slots_[front_].sequence;
  }

  // Number of writes so far (any thread; for statistics).
  std::uint64_t writeCount() const {
    std::lock_guard lock(write_mutex_);
    return write_count_;
  }

 private:
  static constexpr std::uint8_t kIndexMask = 0x3;
  static constexpr std::uint8_t kFreshBit = 0x4;

  struct Slot {
    T value{};
    std::uint64_t sequence = 0;  // 0: never written
  };

  void takeFresh() noexcept {
    if ((middle_.load(std::memory_order_relaxed) & kFreshBit) == 0) return;
    const std::uint8_t previous = middle_.exchange(front_, std::memory_order_acq_rel);
    front_ = previous & kIndexMask;
  }

  std::array<Slot, 3> slots_;
  alignas(64) std::atomic<std::uint8_t> middle_{1};  // slot index | kFreshBit when unread
  alignas(64) std::uint8_t front_ = 0;               // reader's slot
  std::uint64_t cleared_up_to_ = 0;                  // reader: sequences <= this are hidden
  alignas(64) std::uint8_t back_ = 2;                // writer's slot (under write_mutex_)
  std::uint64_t write_count_ = 0;                    // under write_mutex_
  mutable std::mutex write_mutex_;
};

}  // namespace servoloop::realtime
