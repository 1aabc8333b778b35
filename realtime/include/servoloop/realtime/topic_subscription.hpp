#pragma once
// The handle of a non-real-time subscription (TopicBus::subscribe /
// subscribeAny). Destroying or reset()ting it unsubscribes; once that
// returns, the callback is not running and will not be called again — unless
// it is done from inside a callback, which is allowed and simply stops
// further calls.
#include <atomic>
#include <memory>
#include <string>
#include <utility>

namespace servoloop::realtime {

namespace detail {
class BusCore;

struct SubscriberEntryBase {
  virtual ~SubscriberEntryBase() = default;
  std::atomic<bool> active{true};  // cleared on unsubscribe, checked before every call
};

// Non-real-time: removes the subscriber and waits out a callback in progress.
void detachSubscriber(const std::weak_ptr<BusCore>& core, const std::string& topic,
                      const std::shared_ptr<SubscriberEntryBase>& entry);
}  // namespace detail

class Subscription {
 public:
  Subscription() = default;
  Subscription(std::weak_ptr<detail::BusCore> core, std::string topic,
               std::shared_ptr<detail::SubscriberEntryBase> entry)
      : core_(std::move(core)), topic_(std::move(topic)), entry_(std::move(entry)) {}
  Subscription(Subscription&& other) noexcept = default;
  Subscription& operator=(Subscription&& other) noexcept {
    if (this != &other) {
      reset();
      core_ = std::move(other.core_);
      topic_ = std::move(other.topic_);
      entry_ = std::move(other.entry_);
    }
    return *this;
  }
  Subscription(const Subscription&) = delete;
  Subscription& operator=(const Subscription&) = delete;
  ~Subscription() { reset(); }

  void reset() {
    if (entry_) detail::detachSubscriber(core_, topic_, entry_);
    entry_.reset();
  }

  bool active() const noexcept { return entry_ && entry_->active.load(); }
  const std::string& topic() const noexcept { return topic_; }

 private:
  std::weak_ptr<detail::BusCore> core_;
  std::string topic_;
  std::shared_ptr<detail::SubscriberEntryBase> entry_;
};

}  // namespace servoloop::realtime
