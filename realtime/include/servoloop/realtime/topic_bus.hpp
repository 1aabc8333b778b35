#pragma once
// Named, typed topics inside one servoloop node — the part of ROS topics that
// ros_control controllers use — with a real-time-safe path in both directions:
//
//  - RealtimePublisher (advertise): the real-time thread publishes without
//    allocating or blocking; the bus's delivery thread hands the messages to
//    subscribers later (realtime_publisher.hpp).
//  - RealtimeSubscriber (commandInput): the real-time thread reads the latest
//    value published on a topic without blocking (realtime_subscriber.hpp).
//  - subscribe / subscribeAny: non-real-time callbacks on the delivery
//    thread, typed or for any type (the node's `topic echo` and recorder turn
//    those into JSON: servoloop/node/message_json.hpp).
//  - publish / publishView: non-real-time publishing (`topic pub`, tests).
//
// A topic takes its type from the first typed use; any later use with another
// type throws servoloop::Error naming both types. Topic names follow ROS
// rules; relative names are taken relative to "/".
//
// Everything here is non-real-time except what realtime_publisher.hpp and
// realtime_subscriber.hpp mark real-time, and setTime()/now().
//
// Callbacks run on the delivery thread (or in flush()). Destroying a
// Subscription waits for a callback in progress, so do not destroy one while
// holding a lock that a callback of the same bus may be waiting for.
// Plugins: the built-in message types are instantiated inside this library
// (see the end of this file), so topics outlive the plugin that made them. A
// message type defined in a plugin lives in that plugin's code: drop its
// handles before the plugin is unloaded, and do not reuse the topic afterwards.
#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "servoloop/realtime/messages.hpp"
#include "servoloop/realtime/realtime_publisher.hpp"
#include "servoloop/realtime/realtime_subscriber.hpp"
#include "servoloop/realtime/detail/topic_internal.hpp"
#include "servoloop/realtime/topic_subscription.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/time.hpp"

namespace servoloop::realtime {

struct TopicInfo {
  std::string name;
  std::string type;             // "" while only untyped subscribers know the topic
  std::size_t publishers = 0;   // real-time publishers (advertise)
  std::size_t subscribers = 0;  // callbacks, untyped callbacks and command inputs
};

class TopicBus {
 public:
  // Messages a real-time publisher can queue before the oldest is dropped.
  static constexpr std::size_t kDefaultQueueDepth = 16;

  TopicBus();
  // Stops the delivery thread. Handles (publishers, subscribers, subscriptions)
  // may outlive the bus; they then do nothing.
  ~TopicBus();
  TopicBus(const TopicBus&) = delete;
  TopicBus& operator=(const TopicBus&) = delete;

  // --- configure time ------------------------------------------------------------

  // A real-time publisher on topic. prototype sizes every message slot (give
  // it the joint names and vector lengths the real-time thread will publish).
  template <class Msg>
  RealtimePublisher<Msg> advertise(std::string_view topic, const Msg& prototype = Msg{},
                                   std::size_t queue_depth = kDefaultQueueDepth);

  // A latest-value input the real-time thread reads (RealtimeSubscriber);
  // prototype sizes its buffers.
  template <class Msg>
  RealtimeSubscriber<Msg> commandInput(std::string_view topic, const Msg& prototype = Msg{});

  // A callback on the delivery thread for every message on topic, in
  // publishing order per publisher. Keep the Subscription: destroying it unsubscribes.
  template <class Msg>
  [[nodiscard]] Subscription subscribe(std::string_view topic, std::function<void(const Msg&)> callback);

  // Like subscribe, for any type (MessageView). The topic need not exist yet
  // (it is then listed with an empty type until someone types it).
  [[nodiscard]] Subscription subscribeAny(std::string_view topic, AnyCallback callback);

  // --- non-real-time publishing -----------------------------------------------------

  // Command inputs see msg at once, callbacks on the next delivery pass.
  template <class Msg>
  void publish(std::string_view topic, const Msg& msg);

  // Publishes a message whose type is known at run time: msg.type must be a
  // type of messages.hpp (the topic is made if needed) or the type of an
  // existing topic, and match the topic's type. Errors name the topic.
  void publishView(std::string_view topic, const MessageView& msg);

  // --- introspection ------------------------------------------------------------------

  bool hasTopic(std::string_view topic) const;
  // The topic's type name, "" if not known yet; throws for an unknown topic
  // (naming the topics there are).
  std::string typeOf(std::string_view topic) const;
  // Every topic, sorted by name.
  std::vector<TopicInfo> list() const;

  // --- delivery -----------------------------------------------------------------------

  // Starts the delivery thread, which drains publishers every period while a
  // real-time publisher has somebody listening; otherwise it looks again every
  // kIdleDeliveryPeriod (a bus nobody listens to, or whose topics only
  // non-real-time code publishes, costs no wake-ups), and a subscription, a
  // publisher or a non-real-time publish with a subscriber wakes it at once.
  void start(std::chrono::microseconds period = std::chrono::milliseconds(1));
  static constexpr std::chrono::milliseconds kIdleDeliveryPeriod{100};
  // Stops it after one last delivery pass. Idempotent.
  void stop();
  bool running() const;

  // Delivers everything published so far on the calling thread, whether or
  // not the delivery thread runs (the two never deliver at once); returns the
  // number of messages delivered. Must not be called from a callback.
  std::size_t flush();
  void waitForDelivery() { flush(); }

  // --- time -------------------------------------------------------------------------

  // Real-time: the control loop sets the time messages are stamped with.
  void setTime(Time now) noexcept { core_->clock->set(now); }
  Time now() const noexcept { return core_->clock->now(); }

  // "/a/b" for "/a/b", "a/b" or "/a//b/"; throws servoloop::Error for names
  // that break ROS naming rules (segments of letters, digits and '_', not
  // starting with a digit).
  static std::string normalizeTopicName(std::string_view topic);

 private:
  // The delivery thread and what wakes it (topic_bus.cpp), kept out of this
  // header so that controllers including it do not parse <thread>.
  struct DeliveryThread;
  // Non-real-time: the delivery thread looks again now (something changed
  // what it must poll for, or a non-real-time publish waits). No-op without one.
  void wakeDelivery();

  std::shared_ptr<detail::BusCore> core_;
  std::unique_ptr<DeliveryThread> delivery_;
};

// --- template definitions (deliberately not inline: see the extern templates below)

template <class Msg>
RealtimePublisher<Msg> TopicBus::advertise(std::string_view topic, const Msg& prototype, std::size_t queue_depth) {
  const std::string name = normalizeTopicName(topic);
  if (queue_depth == 0) throw Error("advertise '" + name + "': queue_depth must be at least 1");
  auto channel = std::make_shared<detail::PublisherChannel<Msg>>(prototype, queue_depth, core_->clock, core_->work);
  {
    std::lock_guard lock(core_->structure_mutex);
    detail::Topic<Msg>& target = core_->typedTopicLocked<Msg>(name);
    target.publishers.push_back(channel);
    target.updateListened();
  }
  wakeDelivery();
  return RealtimePublisher<Msg>(core_, name, std::move(channel));
}

template <class Msg>
RealtimeSubscriber<Msg> TopicBus::commandInput(std::string_view topic, const Msg& prototype) {
  const std::string name = normalizeTopicName(topic);
  auto buffer = std::make_shared<RealtimeBuffer<Msg>>(prototype);
  {
    std::lock_guard lock(core_->structure_mutex);
    detail::Topic<Msg>& target = core_->typedTopicLocked<Msg>(name);
    target.command_inputs.push_back(buffer);
    target.updateListened();
  }
  wakeDelivery();
  return RealtimeSubscriber<Msg>(core_, name, std::move(buffer));
}

template <class Msg>
Subscription TopicBus::subscribe(std::string_view topic, std::function<void(const Msg&)> callback) {
  const std::string name = normalizeTopicName(topic);
  auto entry = std::make_shared<detail::TypedSubscriberEntry<Msg>>(std::move(callback));
  {
    std::lock_guard lock(core_->structure_mutex);
    detail::Topic<Msg>& target = core_->typedTopicLocked<Msg>(name);
    target.subscribers.push_back(entry);
    target.updateListened();
  }
  wakeDelivery();
  return Subscription(core_, name, std::move(entry));
}

template <class Msg>
void TopicBus::publish(std::string_view topic, const Msg& msg) {
  const std::string name = normalizeTopicName(topic);
  bool queued = false;
  {
    std::lock_guard lock(core_->structure_mutex);
    queued = core_->typedTopicLocked<Msg>(name).publishLocked(msg, core_->clock->now());
    if (queued) core_->work->exchange(true, std::memory_order_release);
  }
  // Nothing queued (no subscriber; command inputs have it already): nothing
  // for the delivery thread to do.
  if (queued) wakeDelivery();
}

// The built-in message types are instantiated once, in the library, so that
// objects the bus keeps never point into a plugin that may be unloaded.
#define SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(MSG, EXTERN)                                                     \
  EXTERN template class detail::Topic<MSG>;                                                                 \
  EXTERN template RealtimePublisher<MSG> TopicBus::advertise<MSG>(std::string_view, const MSG&, std::size_t); \
  EXTERN template RealtimeSubscriber<MSG> TopicBus::commandInput<MSG>(std::string_view, const MSG&);        \
  EXTERN template Subscription TopicBus::subscribe<MSG>(std::string_view, std::function<void(const MSG&)>);  \
  EXTERN template void TopicBus::publish<MSG>(std::string_view, const MSG&);

SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(std_msgs::Float64, extern)
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(std_msgs::Float64MultiArray, extern)
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(std_msgs::Bool, extern)
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(diagnostic_msgs::DiagnosticArray, extern)
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(sensor_msgs::JointState, extern)
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(control_msgs::JointControllerState, extern)
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(nav_msgs::Odometry, extern)
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(gazebo_msgs::ModelStates, extern)
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(geometry_msgs::WrenchStamped, extern)
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(sensor_msgs::Imu, extern)
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(gazebo_msgs::ContactsState, extern)
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(trajectory_msgs::JointTrajectory, extern)
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(control_msgs::JointTrajectoryControllerState, extern)
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(geometry_msgs::Twist, extern)
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(tf2_msgs::TFMessage, extern)

}  // namespace servoloop::realtime
