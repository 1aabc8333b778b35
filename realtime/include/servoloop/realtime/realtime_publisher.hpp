#pragma once
// Publishing from the real-time thread. TopicBus::advertise<Msg>() returns a
// RealtimePublisher at configure time; on the real-time thread it is used
// the way ros_control's realtime_tools publisher is:
//
//   if (state_pub_.trylock()) {
//     state_pub_.msg().set_point = setpoint;
//     state_pub_.unlockAndPublish();
//   }
//
// or with publish(msg). Either copies the message into one of a fixed set of
// slots pre-sized at advertise time and queues it for the bus's delivery
// thread: no allocation (as long as the message is no larger than the
// prototype given to advertise), no lock, no waiting for subscribers. When
// subscribers fall behind and the queue is full, the oldest queued message is
// dropped, so a slow subscriber loses old messages and later gets the newest.
// A topic nobody subscribes to costs a publisher no copy: a subscriber gets
// what is published from its subscription on, as in ROS.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "servoloop/realtime/detail/realtime_index_queue.hpp"
#include "servoloop/realtime/topic_clock.hpp"
#include "servoloop/core/time.hpp"

namespace servoloop::realtime {

namespace detail {

class BusCore;

// What the bus needs to know about a publisher without knowing its type.
class PublisherChannelBase {
 public:
  virtual ~PublisherChannelBase() = default;
  // Set (non-real-time) when the owning RealtimePublisher is destroyed; the
  // delivery thread delivers what is still queued and then forgets the channel.
  std::atomic<bool> closed{false};
  std::atomic<std::uint64_t> published{0};  // messages published (queued, or nobody listened)
  std::atomic<std::uint64_t> dropped{0};    // messages lost to a full queue
  // Set by the bus (structure lock held) whenever the topic's subscribers or
  // command inputs change: while nobody listens, a publish is counted and
  // not copied, so the delivery side finds nothing to hand out.
  std::atomic<bool> listened{false};
};

// The slots and queues of one real-time publisher. One publishing thread at a
// time (the staging lock enforces it for trylock users), one delivering thread.
template <class Msg>
class PublisherChannel : public PublisherChannelBase {
 public:
  // bus_work is the bus's "something to deliver" flag, set after each queued message.
  PublisherChannel(const Msg& prototype, std::size_t queue_depth, std::shared_ptr<const TopicClock> clock,
                   std::shared_ptr<std::atomic<bool>> bus_work)
      : staging_(prototype),
        slots_(queue_depth + 1, Slot{prototype, Time()}),  // + the one being delivered
        ready_(queue_depth + 1),
        // One cell more than there are slots: a push into free_ then never
        // meets the cell of a pop still in progress one lap back.
        free_(queue_depth + 2),
        clock_(std::move(clock)),
        bus_work_(std::move(bus_work)) {
    for (std::uint32_t i = 0; i < slots_.size(); ++i) free_.push(i);
  }

  // Real-time.
  bool trylock() noexcept { return !staging_locked_.test_and_set(std::memory_order_acquire); }
  Msg& staging() noexcept { return staging_; }
  void unlock() noexcept { staging_locked_.clear(std::memory_order_release); }

  // Real-time: copies msg into a slot and queues it; false if it was dropped.
  // Nobody listening: counted as published, not copied.
  bool push(const Msg& msg) noexcept {
    if (!listened.load(std::memory_order_acquire)) {
      published.fetch_add(1, std::memory_order_relaxed);
      return true;
    }
    std::uint32_t index = 0;
    if (!acquireSlot(index)) {
      dropped.fetch_add(1, std::memory_order_relaxed);
      return false;
    }
    Slot& slot = slots_[index];
    slot.msg = msg;
    slot.stamp = clock_->now();
    if (!ready_.push(index)) {
      // The delivery thread was interrupted in the middle of taking a message
      // from ready_, and this publisher has since gone round the whole queue
      // (dropping the oldest each time): the cell it would write is still
      // that message's. This message is dropped and its slot goes back to
      // free_, so no slot is ever lost; ready_ works again once the delivery
      // thread runs on.
      free_.push(index);
      dropped.fetch_add(1, std::memory_order_relaxed);
      bus_work_->exchange(true, std::memory_order_release);
      return false;
    }
    published.fetch_add(1, std::memory_order_relaxed);
    // After the message is in ready_: a delivery pass that sees the flag sees
    // it. Every setter writes the flag with a read-modify-write, so the pass's
    // exchange synchronises with all of them, not only with the last one.
    bus_work_->exchange(true, std::memory_order_release);
    return true;
  }

  // Any thread, a hint: false when no published message waits (one being
  // published right now may or may not be seen; the next pass delivers it).
  bool mayHoldMessages() const noexcept { return ready_.mayHoldValues(); }

  // Delivery thread: hands every queued message, oldest first, to
  // deliver(const Msg&, Time) and recycles its slot. Returns the count.
  template <class Deliver>
  std::size_t drain(Deliver&& deliver) {
    std::size_t count = 0;
    std::uint32_t index = 0;
    while (ready_.pop(index)) {
      struct Recycle {  // the slot goes back even if deliver throws
        RealtimeIndexQueue& free;
        std::uint32_t index;
        ~Recycle() { free.push(index); }
      } recycle{free_, index};
      ++count;
      deliver(static_cast<const Msg&>(slots_[index].msg), slots_[index].stamp);
    }
    return count;
  }

 private:
  struct Slot {
    Msg msg;
    Time stamp;
  };

  // A free slot, or else the oldest queued one (its message is dropped). Both
  // queues can look empty for an instant while the delivery thread moves a
  // slot from one to the other, hence the few retries.
  bool acquireSlot(std::uint32_t& index) noexcept {
    for (int attempt = 0; attempt < 4; ++attempt) {
      if (free_.pop(index)) return true;
      if (ready_.pop(index)) {
        dropped.fetch_add(1, std::memory_order_relaxed);
        return true;
      }
    }
    return false;
  }

  Msg staging_;
  std::atomic_flag staging_locked_ = ATOMIC_FLAG_INIT;
  std::vector<Slot> slots_;
  RealtimeIndexQueue ready_;  // published, oldest first
  RealtimeIndexQueue free_;   // ready to be written
  std::shared_ptr<const TopicClock> clock_;
  std::shared_ptr<std::atomic<bool>> bus_work_;
};

// Non-real-time: tells the bus (if it still exists) that a publisher is gone.
void detachPublisher(const std::weak_ptr<BusCore>& core, const std::string& topic,
                     const std::shared_ptr<PublisherChannelBase>& channel);

}  // namespace detail

template <class Msg>
class RealtimePublisher {
 public:
  // An unconnected publisher (valid() is false); assign one from advertise().
  RealtimePublisher() = default;
  RealtimePublisher(std::weak_ptr<detail::BusCore> core, std::string topic,
                    std::shared_ptr<detail::PublisherChannel<Msg>> channel)
      : core_(std::move(core)), topic_(std::move(topic)), channel_(std::move(channel)) {}

  RealtimePublisher(RealtimePublisher&& other) noexcept = default;
  RealtimePublisher& operator=(RealtimePublisher&& other) noexcept {
    if (this != &other) {
      reset();
      core_ = std::move(other.core_);
      topic_ = std::move(other.topic_);
      channel_ = std::move(other.channel_);
    }
    return *this;
  }
  RealtimePublisher(const RealtimePublisher&) = delete;
  RealtimePublisher& operator=(const RealtimePublisher&) = delete;

  // Non-real-time: stops publishing; messages already queued are still delivered.
  ~RealtimePublisher() { reset(); }
  void reset() {
    if (channel_) detail::detachPublisher(core_, topic_, channel_);
    channel_.reset();
  }

  bool valid() const noexcept { return channel_ != nullptr; }
  const std::string& topic() const noexcept { return topic_; }

  // Real-time: takes the staging message msg(); false if another thread holds it.
  // The staging message keeps its contents between publishes (fill the joint
  // names once, then only the changing fields).
  bool trylock() noexcept { return channel_ && channel_->trylock(); }
  Msg& msg() noexcept { return channel_->staging(); }
  // Real-time: publishes msg() and releases it.
  void unlockAndPublish() noexcept {
    channel_->push(channel_->staging());
    channel_->unlock();
  }
  // Real-time: releases msg() without publishing.
  void unlock() noexcept { channel_->unlock(); }

  // Real-time: publishes a copy of msg (independent of msg()); false if the
  // message was dropped because every slot was busy.
  bool publish(const Msg& msg) noexcept { return channel_ && channel_->push(msg); }

  // Counts since advertise (any thread).
  std::uint64_t publishedCount() const noexcept { return channel_ ? channel_->published.load() : 0; }
  std::uint64_t droppedCount() const noexcept { return channel_ ? channel_->dropped.load() : 0; }

 private:
  std::weak_ptr<detail::BusCore> core_;
  std::string topic_;
  std::shared_ptr<detail::PublisherChannel<Msg>> channel_;
};

}  // namespace servoloop::realtime
