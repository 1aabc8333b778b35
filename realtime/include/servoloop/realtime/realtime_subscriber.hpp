#pragma once
// Receiving on the real-time thread: a command input. TopicBus::commandInput<Msg>()
// returns one at configure time; whatever is published on the topic (a CLI
// `topic pub`, a test, another controller) becomes its latest value, and the
// real-time thread reads that value without blocking or allocating:
//
//   if (const std_msgs::Float64* command = command_.latest()) setpoint = command->data;
//
// Latest-value semantics: values published between two reads are skipped.
#include <memory>
#include <string>
#include <utility>

#include "servoloop/realtime/realtime_buffer.hpp"

namespace servoloop::realtime {

namespace detail {
class BusCore;
// Non-real-time: tells the bus (if it still exists) that a command input is gone.
void detachCommandInput(const std::weak_ptr<BusCore>& core, const std::string& topic, const void* buffer);
}  // namespace detail

template <class Msg>
class RealtimeSubscriber {
 public:
  // An unconnected subscriber (valid() is false); assign one from commandInput().
  RealtimeSubscriber() = default;
  RealtimeSubscriber(std::weak_ptr<detail::BusCore> core, std::string topic,
                     std::shared_ptr<RealtimeBuffer<Msg>> buffer)
      : buffer_(std::move(buffer)), core_(std::move(core)), topic_(std::move(topic)) {}

  RealtimeSubscriber(RealtimeSubscriber&& other) noexcept = default;
  RealtimeSubscriber& operator=(RealtimeSubscriber&& other) noexcept {
    if (this != &other) {
      reset();
      core_ = std::move(other.core_);
      topic_ = std::move(other.topic_);
      buffer_ = std::move(other.buffer_);
    }
    return *this;
  }
  RealtimeSubscriber(const RealtimeSubscriber&) = delete;
  RealtimeSubscriber& operator=(const RealtimeSubscriber&) = delete;

  // Non-real-time: unsubscribes.
  ~RealtimeSubscriber() { reset(); }
  void reset() {
    if (buffer_) detail::detachCommandInput(core_, topic_, buffer_.get());
    buffer_.reset();
  }

  bool valid() const noexcept { return buffer_ != nullptr; }
  const std::string& topic() const noexcept { return topic_; }

  // Real-time, one reading thread: the newest message, or nullptr if none
  // arrived since the input was made or last clear()ed. Valid until the next
  // latest()/readLatest()/clear() call.
  const Msg* latest() noexcept { return buffer_ ? buffer_->readFromRT() : nullptr; }

  // Real-time: copies the newest message into out; false (out untouched) if none.
  // No allocation when out's vectors are at least as long as the message's.
  bool readLatest(Msg& out) { return buffer_ && buffer_->readFromRT(out); }

  // Real-time: whether a message arrived since the last latest()/readLatest().
  bool hasNewMessage() const noexcept { return buffer_ && buffer_->newDataAvailable(); }

  // Real-time: forgets the current value (e.g. in a controller's starting()).
  void clear() noexcept {
    if (buffer_) buffer_->clearFromRT();
  }

 private:
  std::shared_ptr<RealtimeBuffer<Msg>> buffer_;  // first: what a real-time reader uses
  std::weak_ptr<detail::BusCore> core_;
  std::string topic_;
};

}  // namespace servoloop::realtime
