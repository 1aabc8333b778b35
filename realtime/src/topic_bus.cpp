#include "servoloop/realtime/topic_bus.hpp"

#include <condition_variable>
#include <thread>

#include "servoloop/core/logging.hpp"

namespace servoloop::realtime {

namespace {

// True on a thread while it runs a delivery pass (callbacks run inside one).
thread_local bool t_in_delivery = false;

struct InDeliveryScope {
  InDeliveryScope() { t_in_delivery = true; }
  ~InDeliveryScope() { t_in_delivery = false; }
  InDeliveryScope(const InDeliveryScope&) = delete;
  InDeliveryScope& operator=(const InDeliveryScope&) = delete;
};

bool isNameStart(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool isNameChar(char c) { return isNameStart(c) || (c >= '0' && c <= '9'); }

std::string topicNames(const std::map<std::string, std::shared_ptr<detail::TopicBase>>& topics) {
  if (topics.empty()) return "there are no topics yet";
  std::string names = "topics are: ";
  bool first = true;
  for (const auto& [name, topic] : topics) {
    names += (first ? "" : ", ") + name;
    first = false;
  }
  return names;
}

std::string knownTypesText() {
  std::string text;
  for (std::string_view type : {std_msgs::Float64::kTypeName, std_msgs::Float64MultiArray::kTypeName,
                                std_msgs::Bool::kTypeName, diagnostic_msgs::DiagnosticArray::kTypeName,
                                sensor_msgs::JointState::kTypeName, control_msgs::JointControllerState::kTypeName,
                                nav_msgs::Odometry::kTypeName, trajectory_msgs::JointTrajectory::kTypeName,
                                control_msgs::JointTrajectoryControllerState::kTypeName,
                                geometry_msgs::Twist::kTypeName, tf2_msgs::TFMessage::kTypeName,
                                gazebo_msgs::ModelStates::kTypeName, geometry_msgs::WrenchStamped::kTypeName,
                                sensor_msgs::Imu::kTypeName, gazebo_msgs::ContactsState::kTypeName}) {
    text += (text.empty() ? "" : ", ") + std::string(type);
  }
  return text;
}

}  // namespace

namespace detail {

void reportCallbackError(const std::string& topic, const char* what) {
  logger().error("topic '{}': a subscriber callback threw: {}", topic, what);
}

bool TopicBase::publishViewLocked(const MessageView& /*msg*/, Time /*stamp*/) {
  throw Error("topic '" + name_ +
              "' has no type yet (only untyped subscribers know it); give the message type to publish on it");
}

void throwTypeMismatch(const std::string& topic, std::string_view existing_type, std::string_view requested_type) {
  throw Error("topic '" + topic + "' carries " + std::string(existing_type) + ", not " +
              std::string(requested_type) + "; use " + std::string(existing_type) +
              " on it or pick another topic name");
}

BusCore::BusCore() : clock(std::make_shared<TopicClock>()) {}

TopicBase& BusCore::topicForTypeLocked(const std::string& name, std::string_view type_name) {
  if (type_name == std_msgs::Float64::kTypeName) return typedTopicLocked<std_msgs::Float64>(name);
  if (type_name == std_msgs::Float64MultiArray::kTypeName) return typedTopicLocked<std_msgs::Float64MultiArray>(name);
  if (type_name == std_msgs::Bool::kTypeName) return typedTopicLocked<std_msgs::Bool>(name);
  if (type_name == diagnostic_msgs::DiagnosticArray::kTypeName) {
    return typedTopicLocked<diagnostic_msgs::DiagnosticArray>(name);
  }
  if (type_name == sensor_msgs::JointState::kTypeName) return typedTopicLocked<sensor_msgs::JointState>(name);
  if (type_name == control_msgs::JointControllerState::kTypeName) {
    return typedTopicLocked<control_msgs::JointControllerState>(name);
  }
  if (type_name == nav_msgs::Odometry::kTypeName) return typedTopicLocked<nav_msgs::Odometry>(name);
  if (type_name == trajectory_msgs::JointTrajectory::kTypeName) {
    return typedTopicLocked<trajectory_msgs::JointTrajectory>(name);
  }
  if (type_name == control_msgs::JointTrajectoryControllerState::kTypeName) {
    return typedTopicLocked<control_msgs::JointTrajectoryControllerState>(name);
  }
  if (type_name == geometry_msgs::Twist::kTypeName) return typedTopicLocked<geometry_msgs::Twist>(name);
  if (type_name == tf2_msgs::TFMessage::kTypeName) return typedTopicLocked<tf2_msgs::TFMessage>(name);
  if (type_name == gazebo_msgs::ModelStates::kTypeName) return typedTopicLocked<gazebo_msgs::ModelStates>(name);
  if (type_name == geometry_msgs::WrenchStamped::kTypeName) {
    return typedTopicLocked<geometry_msgs::WrenchStamped>(name);
  }
  if (type_name == sensor_msgs::Imu::kTypeName) return typedTopicLocked<sensor_msgs::Imu>(name);
  if (type_name == gazebo_msgs::ContactsState::kTypeName) return typedTopicLocked<gazebo_msgs::ContactsState>(name);
  // A type only a plugin knows can still be used once that plugin typed the topic.
  auto it = topics.find(name);
  if (it != topics.end() && it->second->type() == type_name) return *it->second;
  throw Error("unknown message type '" + std::string(type_name) + "' for topic '" + name +
              "'; known types: " + knownTypesText());
}

std::size_t BusCore::deliverOnce() {
  std::lock_guard delivery(delivery_mutex);
  if (!work->exchange(false, std::memory_order_acq_rel)) return 0;  // nothing was queued since the last pass
  // A pass that throws (out of memory) has not delivered everything: the next one must look again.
  struct RetryUnlessDone {
    std::atomic<bool>& work;
    bool done = false;
    ~RetryUnlessDone() {
      if (!done) work.exchange(true, std::memory_order_release);
    }
  } retry{*work};
  InDeliveryScope scope;
  std::vector<std::shared_ptr<TopicBase>> snapshot;
  {
    std::lock_guard lock(structure_mutex);
    snapshot.reserve(topics.size());
    for (const auto& [name, topic] : topics) snapshot.push_back(topic);
  }
  std::size_t count = 0;
  for (const auto& topic : snapshot) count += topic->deliver(structure_mutex);
  retry.done = true;
  return count;
}

void detachPublisher(const std::weak_ptr<BusCore>& weak_core, const std::string& /*topic*/,
                     const std::shared_ptr<PublisherChannelBase>& channel) {
  // The delivery thread delivers what is still queued, then drops the channel.
  if (auto core = weak_core.lock()) {
    std::lock_guard lock(core->structure_mutex);
    channel->closed.store(true, std::memory_order_release);
    core->work->exchange(true, std::memory_order_release);
  }
}

void detachCommandInput(const std::weak_ptr<BusCore>& weak_core, const std::string& topic, const void* buffer) {
  auto core = weak_core.lock();
  if (!core) return;
  std::lock_guard lock(core->structure_mutex);
  if (auto it = core->topics.find(topic); it != core->topics.end()) it->second->removeCommandInput(buffer);
}

void detachSubscriber(const std::weak_ptr<BusCore>& weak_core, const std::string& topic,
                      const std::shared_ptr<SubscriberEntryBase>& entry) {
  entry->active.store(false);
  auto core = weak_core.lock();
  if (!core) return;
  {
    std::lock_guard lock(core->structure_mutex);
    if (auto it = core->topics.find(topic); it != core->topics.end()) it->second->removeSubscriber(entry.get());
  }
  // Wait out a callback that may be running right now, unless we are inside one.
  if (!t_in_delivery) std::lock_guard wait_for_pass(core->delivery_mutex);
}

}  // namespace detail

struct TopicBus::DeliveryThread {
  mutable std::mutex mutex;
  std::condition_variable wake;
  std::thread thread;
  bool stop_requested = false;
  bool woken = false;  // wakeDelivery() since the thread last looked
};

namespace {
// Whether a real-time publisher may queue messages that somebody waits for:
// then the delivery thread polls every period; else nothing reaches a
// subscriber but through a call that wakes it.
bool pollingNeeded(detail::BusCore& core) {
  std::lock_guard lock(core.structure_mutex);
  for (const auto& [name, topic] : core.topics) {
    if (topic->publisherCount() > 0 && topic->subscriberCount() > 0) return true;
  }
  return false;
}
}  // namespace

TopicBus::TopicBus() : core_(std::make_shared<detail::BusCore>()), delivery_(std::make_unique<DeliveryThread>()) {}

TopicBus::~TopicBus() { stop(); }

std::string TopicBus::normalizeTopicName(std::string_view topic) {
  std::string result;
  std::size_t start = 0;
  while (start <= topic.size()) {
    std::size_t end = topic.find('/', start);
    if (end == std::string_view::npos) end = topic.size();
    const std::string_view segment = topic.substr(start, end - start);
    if (!segment.empty()) {
      const bool valid = isNameStart(segment.front()) &&
                         std::all_of(segment.begin(), segment.end(), [](char c) { return isNameChar(c); });
      if (!valid) {
        throw Error("invalid topic name '" + std::string(topic) + "': each part between '/' must start with a " +
                    "letter or '_' and contain only letters, digits and '_'");
      }
      result += "/";
      result += segment;
    }
    start = end + 1;
  }
  if (result.empty()) throw Error("invalid topic name '" + std::string(topic) + "': it is empty");
  return result;
}

Subscription TopicBus::subscribeAny(std::string_view topic, AnyCallback callback) {
  const std::string name = normalizeTopicName(topic);
  auto entry = std::make_shared<detail::AnySubscriberEntry>(std::move(callback));
  {
    std::lock_guard lock(core_->structure_mutex);
    auto it = core_->topics.find(name);
    if (it == core_->topics.end()) it = core_->topics.emplace(name, std::make_shared<detail::TopicBase>(name)).first;
    it->second->any_subscribers.push_back(entry);
    it->second->updateListened();
  }
  wakeDelivery();
  return Subscription(core_, name, std::move(entry));
}

void TopicBus::publishView(std::string_view topic, const MessageView& msg) {
  const std::string name = normalizeTopicName(topic);
  bool queued = false;
  {
    std::lock_guard lock(core_->structure_mutex);
    detail::TopicBase& target = core_->topicForTypeLocked(name, msg.type);
    if (target.type() != msg.type) detail::throwTypeMismatch(name, target.type(), msg.type);
    queued = target.publishViewLocked(msg, core_->clock->now());
    if (queued) core_->work->exchange(true, std::memory_order_release);
  }
  if (queued) wakeDelivery();
}

bool TopicBus::hasTopic(std::string_view topic) const {
  const std::string name = normalizeTopicName(topic);
  std::lock_guard lock(core_->structure_mutex);
  return core_->topics.contains(name);
}

std::string TopicBus::typeOf(std::string_view topic) const {
  const std::string name = normalizeTopicName(topic);
  std::lock_guard lock(core_->structure_mutex);
  auto it = core_->topics.find(name);
  if (it == core_->topics.end()) throw Error("no topic '" + name + "'; " + topicNames(core_->topics));
  return std::string(it->second->type());
}

std::vector<TopicInfo> TopicBus::list() const {
  std::lock_guard lock(core_->structure_mutex);
  std::vector<TopicInfo> infos;
  infos.reserve(core_->topics.size());
  for (const auto& [name, topic] : core_->topics) {  // std::map: already sorted
    infos.push_back(TopicInfo{name, std::string(topic->type()), topic->publisherCount(), topic->subscriberCount()});
  }
  return infos;
}

void TopicBus::start(std::chrono::microseconds period) {
  DeliveryThread& delivery = *delivery_;
  std::lock_guard lock(delivery.mutex);
  if (delivery.thread.joinable()) return;
  delivery.stop_requested = false;
  delivery.woken = false;
  delivery.thread = std::thread([this, &delivery, period] {
    for (;;) {
      core_->deliverOnce();
      const auto wait = pollingNeeded(*core_) ? std::chrono::duration_cast<std::chrono::microseconds>(period)
                                              : std::chrono::microseconds(kIdleDeliveryPeriod);
      std::unique_lock wait_lock(delivery.mutex);
      delivery.wake.wait_for(wait_lock, wait, [&delivery] { return delivery.stop_requested || delivery.woken; });
      if (delivery.stop_requested) break;
      delivery.woken = false;
    }
    core_->deliverOnce();  // what was published before stop() still arrives
  });
}

void TopicBus::wakeDelivery() {
  DeliveryThread& delivery = *delivery_;
  {
    std::lock_guard lock(delivery.mutex);
    if (!delivery.thread.joinable()) return;
    delivery.woken = true;
  }
  delivery.wake.notify_all();
}

void TopicBus::stop() {
  DeliveryThread& delivery = *delivery_;
  std::thread thread;
  {
    std::lock_guard lock(delivery.mutex);
    if (!delivery.thread.joinable()) return;
    delivery.stop_requested = true;
    thread = std::move(delivery.thread);
  }
  delivery.wake.notify_all();
  thread.join();
}

bool TopicBus::running() const {
  std::lock_guard lock(delivery_->mutex);
  return delivery_->thread.joinable();
}

std::size_t TopicBus::flush() {
  if (t_in_delivery) {
    throw Error("TopicBus::flush() called from a subscriber callback; callbacks already run inside a "
                "delivery pass and must not wait for one");
  }
  return core_->deliverOnce();
}

SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(std_msgs::Float64, )
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(std_msgs::Float64MultiArray, )
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(std_msgs::Bool, )
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(diagnostic_msgs::DiagnosticArray, )
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(sensor_msgs::JointState, )
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(control_msgs::JointControllerState, )
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(nav_msgs::Odometry, )
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(gazebo_msgs::ModelStates, )
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(geometry_msgs::WrenchStamped, )
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(sensor_msgs::Imu, )
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(gazebo_msgs::ContactsState, )
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(trajectory_msgs::JointTrajectory, )
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(control_msgs::JointTrajectoryControllerState, )
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(geometry_msgs::Twist, )
SERVOLOOP_TOPIC_BUS_EXTERN_TEMPLATES(tf2_msgs::TFMessage, )

}  // namespace servoloop::realtime
