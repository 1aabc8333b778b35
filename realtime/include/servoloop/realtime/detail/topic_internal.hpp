#pragma once
// Internals of the topic bus, shared by its templates (topic_bus.hpp) and
// topic_bus.cpp. Not for direct use.
//
// Locking: BusCore::structure_mutex guards the topic map and every list in
// it; BusCore::delivery_mutex is held for a whole delivery pass, so callbacks
// of one bus never run concurrently and an unsubscribe can wait one out.
// Callbacks run with structure_mutex released: they may use the bus.
#include <algorithm>
#include <cstddef>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "servoloop/realtime/message_view.hpp"
#include "servoloop/realtime/realtime_buffer.hpp"
#include "servoloop/realtime/realtime_publisher.hpp"
#include "servoloop/realtime/topic_clock.hpp"
#include "servoloop/realtime/topic_subscription.hpp"
#include "servoloop/core/time.hpp"

namespace servoloop::realtime {

namespace detail {

struct AnySubscriberEntry final : SubscriberEntryBase {
  explicit AnySubscriberEntry(AnyCallback cb) : callback(std::move(cb)) {}
  AnyCallback callback;
};

template <class Msg>
struct TypedSubscriberEntry final : SubscriberEntryBase {
  explicit TypedSubscriberEntry(std::function<void(const Msg&)> cb) : callback(std::move(cb)) {}
  std::function<void(const Msg&)> callback;
};

// Logs (never rethrows) an exception that escaped a subscriber callback.
void reportCallbackError(const std::string& topic, const char* what);

template <class Call>
void invokeGuarded(const std::string& topic, Call&& call) {
  try {
    call();
  } catch (const std::exception& e) {
    reportCallbackError(topic, e.what());
  } catch (...) {
    reportCallbackError(topic, "unknown exception");
  }
}

template <class Entry>
void eraseEntry(std::vector<std::shared_ptr<Entry>>& entries, const void* target) {
  std::erase_if(entries, [target](const auto& entry) { return entry.get() == target; });
}

// A named topic. Untyped (type() empty) while only untyped subscribers know it.
class TopicBase {
 public:
  explicit TopicBase(std::string name) : name_(std::move(name)) {}
  virtual ~TopicBase() = default;
  TopicBase(const TopicBase&) = delete;
  TopicBase& operator=(const TopicBase&) = delete;

  const std::string& name() const { return name_; }
  virtual std::string_view type() const { return {}; }

  // With structure_mutex held.
  virtual std::size_t publisherCount() const { return 0; }
  virtual std::size_t subscriberCount() const { return any_subscribers.size(); }
  // msg.data points to a message of msg.type == type(); throws when untyped.
  // True when a subscriber's copy was queued for the delivery thread.
  virtual bool publishViewLocked(const MessageView& msg, Time stamp);
  virtual void removeCommandInput(const void* /*buffer*/) {}
  virtual void removeSubscriber(const void* entry) {
    eraseEntry(any_subscribers, entry);
    updateListened();
  }
  // With structure_mutex held, after subscribers, command inputs or
  // publishers changed: tells the publishers whether anybody listens.
  virtual void updateListened() {}

  // Delivery pass, structure_mutex NOT held (it is taken briefly inside):
  // hands everything pending to the subscribers; returns the message count.
  virtual std::size_t deliver(std::mutex& /*structure_mutex*/) { return 0; }

  std::vector<std::shared_ptr<AnySubscriberEntry>> any_subscribers;

 private:
  std::string name_;
};

template <class Msg>
class Topic final : public TopicBase {
 public:
  // Messages published from non-real-time threads wait here for the delivery
  // thread; beyond this many the oldest are dropped (no delivery thread running).
  static constexpr std::size_t kMaxPending = 1024;

  using TopicBase::TopicBase;

  std::string_view type() const override { return Msg::kTypeName; }

  std::size_t publisherCount() const override {
    return static_cast<std::size_t>(std::count_if(publishers.begin(), publishers.end(),
                                                  [](const auto& channel) { return !channel->closed.load(); }));
  }
  std::size_t subscriberCount() const override {
    return subscribers.size() + any_subscribers.size() + command_inputs.size();
  }

  // Non-real-time publish, structure_mutex held: command inputs see the value
  // at once, callbacks on the next delivery pass.
  // Command inputs take the message at once; subscribers get it from the
  // delivery thread. True when it was queued for them (there are some).
  bool publishLocked(const Msg& msg, Time stamp) {
    for (const auto& input : command_inputs) input->writeFromNonRT(msg);
    if (subscribers.empty() && any_subscribers.empty()) return false;
    if (pending.size() >= kMaxPending) pending.pop_front();
    pending.push_back(Pending{msg, stamp});
    return true;
  }

  bool publishViewLocked(const MessageView& msg, Time stamp) override {
    return publishLocked(*static_cast<const Msg*>(msg.data), stamp);
  }

  void removeCommandInput(const void* buffer) override {
    eraseEntry(command_inputs, buffer);
    updateListened();
  }
  void removeSubscriber(const void* entry) override {
    eraseEntry(subscribers, entry);
    TopicBase::removeSubscriber(entry);
  }
  void updateListened() override {
    const bool listened = !subscribers.empty() || !any_subscribers.empty() || !command_inputs.empty();
    for (const auto& channel : publishers) channel->listened.store(listened, std::memory_order_release);
  }

  std::size_t deliver(std::mutex& structure_mutex) override {
    // Snapshot under the lock; deliver without it.
    std::vector<std::shared_ptr<PublisherChannel<Msg>>> channels;
    std::vector<std::shared_ptr<TypedSubscriberEntry<Msg>>> typed;
    std::vector<std::shared_ptr<AnySubscriberEntry>> untyped;
    std::vector<std::shared_ptr<RealtimeBuffer<Msg>>> inputs;
    std::deque<Pending> from_non_rt;
    {
      std::lock_guard lock(structure_mutex);
      // Nothing queued and no publisher gone: nothing to copy or deliver. A
      // free-running loop flushes its bus every few steps, mostly to find this.
      const bool idle = pending.empty() && std::none_of(publishers.begin(), publishers.end(), [](const auto& channel) {
                          return channel->mayHoldMessages() || channel->closed.load(std::memory_order_acquire);
                        });
      if (idle) return 0;
      channels = publishers;
      typed = subscribers;
      untyped = any_subscribers;
      inputs = command_inputs;
      from_non_rt.swap(pending);
    }
    const auto dispatch = [&](const Msg& msg, Time stamp) {
      for (const auto& entry : typed) {
        if (entry->active.load()) invokeGuarded(name(), [&] { entry->callback(msg); });
      }
      for (const auto& entry : untyped) {
        if (entry->active.load()) invokeGuarded(name(), [&] { entry->callback(stamp, MessageView{Msg::kTypeName, &msg}); });
      }
    };

    std::size_t count = 0;
    for (const Pending& item : from_non_rt) {
      dispatch(item.msg, item.stamp);
      ++count;
    }
    std::vector<const PublisherChannelBase*> finished;
    for (const auto& channel : channels) {
      // Read before draining: a publisher closes only after its last push.
      const bool was_closed = channel->closed.load(std::memory_order_acquire);
      count += channel->drain([&](const Msg& msg, Time stamp) {
        for (const auto& input : inputs) input->writeFromNonRT(msg);
        dispatch(msg, stamp);
      });
      if (was_closed) finished.push_back(channel.get());
    }
    if (!finished.empty()) {
      std::lock_guard lock(structure_mutex);
      std::erase_if(publishers, [&](const auto& channel) {
        return std::find(finished.begin(), finished.end(), channel.get()) != finished.end();
      });
    }
    return count;
  }

  struct Pending {
    Msg msg;
    Time stamp;
  };

  std::vector<std::shared_ptr<PublisherChannel<Msg>>> publishers;
  std::vector<std::shared_ptr<TypedSubscriberEntry<Msg>>> subscribers;
  std::vector<std::shared_ptr<RealtimeBuffer<Msg>>> command_inputs;
  std::deque<Pending> pending;
};

[[noreturn]] void throwTypeMismatch(const std::string& topic, std::string_view existing_type,
                                    std::string_view requested_type);

class BusCore {
 public:
  BusCore();

  // structure_mutex held: the topic called name as a Topic<Msg>, made if
  // missing, given its type if untyped; throws if it has another type.
  template <class Msg>
  Topic<Msg>& typedTopicLocked(const std::string& name) {
    auto it = topics.find(name);
    if (it == topics.end()) {
      auto topic = std::make_shared<Topic<Msg>>(name);
      topics.emplace(name, topic);
      return *topic;
    }
    const std::string_view existing = it->second->type();
    if (existing.empty()) {
      auto topic = std::make_shared<Topic<Msg>>(name);
      topic->any_subscribers = std::move(it->second->any_subscribers);
      it->second = topic;
      return *topic;
    }
    if (existing != Msg::kTypeName) throwTypeMismatch(name, existing, Msg::kTypeName);
    // Same type name means same message type (plugins are ABI-checked on load).
    return static_cast<Topic<Msg>&>(*it->second);
  }

  // structure_mutex held: a typed topic for a type name of messages.hpp, or
  // an existing topic of that type.
  TopicBase& topicForTypeLocked(const std::string& name, std::string_view type_name);

  // One delivery pass on the calling thread.
  std::size_t deliverOnce();

  std::mutex structure_mutex;
  std::map<std::string, std::shared_ptr<TopicBase>> topics;
  std::mutex delivery_mutex;
  std::shared_ptr<TopicClock> clock;
  // Set whenever something may wait for delivery (a real-time publisher
  // queued a message, a non-real-time publish, a publisher went away);
  // deliverOnce clears it and returns at once when it was clear, so a loop
  // that flushes every few steps pays nothing while nobody listens.
  std::shared_ptr<std::atomic<bool>> work = std::make_shared<std::atomic<bool>>(true);
};

}  // namespace detail
}  // namespace servoloop::realtime
