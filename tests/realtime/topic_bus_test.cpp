// TopicBus: typed topics, real-time publishing with delivery on another
// thread, latest-value command inputs, JSON subscribers and publishers.
#include <atomic>
#include <chrono>
#include <future>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "thrown_message.hpp"
#include "servoloop/node/message_json.hpp"
#include "servoloop/realtime/topic_bus.hpp"

namespace servoloop::realtime {
namespace {

using servoloop::testing::thrownMessage;

using nlohmann::json;
using ::testing::HasSubstr;
using namespace std::chrono_literals;

sensor_msgs::JointState jointStatePrototype() {
  sensor_msgs::JointState msg;
  msg.name = {"j1", "j2", "j3"};
  msg.position.assign(3, 0.0);
  msg.velocity.assign(3, 0.0);
  msg.effort.assign(3, 0.0);
  return msg;
}

TEST(TopicBus, TopicTypeIsFixedByFirstUse) {
  TopicBus bus;
  auto publisher = bus.advertise<std_msgs::Float64>("/robot/ctrl/command");
  const std::string message = thrownMessage([&] {
    auto subscription = bus.subscribe<std_msgs::Float64MultiArray>("/robot/ctrl/command", [](const auto&) {});
  });
  EXPECT_EQ(message,
            "topic '/robot/ctrl/command' carries std_msgs/Float64, not std_msgs/Float64MultiArray; use "
            "std_msgs/Float64 on it or pick another topic name");
  EXPECT_THROW(bus.publish("/robot/ctrl/command", sensor_msgs::JointState{}), Error);
  EXPECT_THROW(bus.commandInput<control_msgs::JointControllerState>("/robot/ctrl/command"), Error);
  EXPECT_THROW(bus.advertise<std_msgs::Float64MultiArray>("robot/ctrl/command"), Error);
  EXPECT_THAT(thrownMessage([&] { servoloop::node::publishJson(bus, "/robot/ctrl/command", json{{"data", 1}}, "sensor_msgs/JointState"); }),
              HasSubstr("carries std_msgs/Float64, not sensor_msgs/JointState"));
  EXPECT_NO_THROW(bus.commandInput<std_msgs::Float64>("/robot/ctrl/command"));
  EXPECT_EQ(bus.typeOf("/robot/ctrl/command"), "std_msgs/Float64");
}

TEST(TopicBus, TopicNamesFollowRosRules) {
  EXPECT_EQ(TopicBus::normalizeTopicName("one_DOF_robot/joint_states"), "/one_DOF_robot/joint_states");
  EXPECT_EQ(TopicBus::normalizeTopicName("//a//b/"), "/a/b");
  EXPECT_THAT(thrownMessage([] { TopicBus::normalizeTopicName("/robot/1st"); }), HasSubstr("'/robot/1st'"));
  EXPECT_THROW(TopicBus::normalizeTopicName("/a b"), Error);
  EXPECT_THROW(TopicBus::normalizeTopicName("/"), Error);
}

TEST(TopicBus, RealtimePublishDeliversExactlyWhatWasPublishedInOrder) {
  TopicBus bus;
  auto publisher = bus.advertise<sensor_msgs::JointState>("/robot/joint_states", jointStatePrototype());
  std::vector<sensor_msgs::JointState> received;
  auto subscription = bus.subscribe<sensor_msgs::JointState>(
      "/robot/joint_states", [&](const sensor_msgs::JointState& msg) { received.push_back(msg); });

  // Fewer than the queue depth, so nothing may be dropped.
  for (int k = 0; k < 10; ++k) {
    ASSERT_TRUE(publisher.trylock());
    publisher.msg().stamp = 0.01 * k;
    for (int j = 0; j < 3; ++j) {
      publisher.msg().position[j] = k + 0.1 * j;
      publisher.msg().velocity[j] = -k;
      publisher.msg().effort[j] = 2.0 * k;
    }
    publisher.unlockAndPublish();
  }
  EXPECT_EQ(bus.flush(), 10u);
  ASSERT_EQ(received.size(), 10u);
  for (int k = 0; k < 10; ++k) {
    EXPECT_EQ(received[k].stamp, 0.01 * k);
    EXPECT_EQ(received[k].name, (std::vector<std::string>{"j1", "j2", "j3"}));  // set once, in the prototype
    EXPECT_EQ(received[k].position, (std::vector<double>{k + 0.0, k + 0.1, k + 0.2}));
    EXPECT_EQ(received[k].velocity, (std::vector<double>(3, -k)));
    EXPECT_EQ(received[k].effort, (std::vector<double>(3, 2.0 * k)));
  }
  EXPECT_EQ(publisher.publishedCount(), 10u);
  EXPECT_EQ(publisher.droppedCount(), 0u);
  EXPECT_EQ(bus.flush(), 0u);
}

TEST(TopicBus, APublisherNobodyListensToQueuesNothingAndListenersGetWhatFollows) {
  TopicBus bus;
  auto publisher = bus.advertise<std_msgs::Float64>("/robot/ctrl/state");
  // Nobody listens: published (counted), nothing queued for delivery.
  for (int k = 0; k < 5; ++k) EXPECT_TRUE(publisher.publish(std_msgs::Float64{static_cast<double>(k)}));
  EXPECT_EQ(publisher.publishedCount(), 5u);
  EXPECT_EQ(publisher.droppedCount(), 0u);
  EXPECT_EQ(bus.flush(), 0u);

  // A subscriber gets what is published from its subscription on.
  std::vector<double> received;
  auto subscription =
      bus.subscribe<std_msgs::Float64>("/robot/ctrl/state", [&](const std_msgs::Float64& msg) { received.push_back(msg.data); });
  for (int k = 10; k < 13; ++k) publisher.publish(std_msgs::Float64{static_cast<double>(k)});
  EXPECT_EQ(bus.flush(), 3u);
  EXPECT_EQ(received, (std::vector<double>{10.0, 11.0, 12.0}));

  // Unsubscribed: nothing is queued again.
  subscription.reset();
  publisher.publish(std_msgs::Float64{20.0});
  EXPECT_EQ(bus.flush(), 0u);
  EXPECT_EQ(publisher.publishedCount(), 9u);

  // A command input of the topic listens too (and so does a subscriber of any
  // type that came before the topic had one).
  auto input = bus.commandInput<std_msgs::Float64>("/robot/ctrl/state");
  publisher.publish(std_msgs::Float64{30.0});
  EXPECT_EQ(bus.flush(), 1u);
  const std_msgs::Float64* latest = input.latest();
  ASSERT_NE(latest, nullptr);
  EXPECT_EQ(latest->data, 30.0);
  input = RealtimeSubscriber<std_msgs::Float64>();
  std::vector<std::string> types;
  auto any = bus.subscribeAny("/robot/other", [&](Time, const MessageView& msg) { types.emplace_back(msg.type); });
  auto other = bus.advertise<std_msgs::Float64>("/robot/other");
  other.publish(std_msgs::Float64{1.0});
  publisher.publish(std_msgs::Float64{40.0});  // nobody on this one any more
  EXPECT_EQ(bus.flush(), 1u);
  EXPECT_EQ(types, (std::vector<std::string>{std::string(std_msgs::Float64::kTypeName)}));
}

// The delivery thread polls only while a real-time publisher has a listener;
// in between it waits, and whatever starts traffic again (a subscription, a
// command input, a publisher, a non-real-time publish) is still delivered.
TEST(TopicBus, ARunningBusDeliversAcrossIdleAndBusySpells) {
  TopicBus bus;
  bus.start();
  std::mutex mutex;
  std::vector<double> received;
  const auto arrived = [&](std::size_t count) {
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (std::chrono::steady_clock::now() < deadline) {
      {
        std::lock_guard lock(mutex);
        if (received.size() >= count) return true;
      }
      std::this_thread::sleep_for(1ms);
    }
    return false;
  };
  const auto record = [&](const std_msgs::Float64& msg) {
    std::lock_guard lock(mutex);
    received.push_back(msg.data);
  };

  // Idle: a publisher nobody listens to.
  auto publisher = bus.advertise<std_msgs::Float64>("/robot/state");
  publisher.publish(std_msgs::Float64{0.0});
  // A subscription starts the traffic: each message arrives, one at a time.
  auto subscription = bus.subscribe<std_msgs::Float64>("/robot/state", record);
  for (int k = 1; k <= 3; ++k) {
    publisher.publish(std_msgs::Float64{static_cast<double>(k)});
    ASSERT_TRUE(arrived(static_cast<std::size_t>(k))) << k;
  }
  // Idle again, then a non-real-time publish to a topic of its own.
  subscription.reset();
  auto other = bus.subscribe<std_msgs::Float64>("/robot/command", record);
  bus.publish("/robot/command", std_msgs::Float64{4.0});
  ASSERT_TRUE(arrived(4));
  // A real-time publisher that comes after its subscriber.
  auto late = bus.advertise<std_msgs::Float64>("/robot/command");
  late.publish(std_msgs::Float64{5.0});
  ASSERT_TRUE(arrived(5));
  bus.stop();
  std::lock_guard lock(mutex);
  EXPECT_EQ(received, (std::vector<double>{1.0, 2.0, 3.0, 4.0, 5.0}));
}

TEST(TopicBus, APassFindsWhatWasQueuedWhileItRanAndForgetsClosedPublishers) {
  TopicBus bus;
  // A publisher closed with nothing queued is forgotten by the next pass.
  {
    auto gone = bus.advertise<std_msgs::Float64>("/robot/gone");
    auto listener = bus.subscribe<std_msgs::Float64>("/robot/gone", [](const std_msgs::Float64&) {});
    EXPECT_EQ(bus.flush(), 0u);
  }
  bus.flush();
  ASSERT_EQ(bus.list().size(), 1u);
  EXPECT_EQ(bus.list()[0].publishers, 0u);

  // A callback of one topic publishes in real time on a topic the same pass
  // has already visited ("/a" comes before "/b"): the next pass delivers it.
  auto a = bus.advertise<std_msgs::Float64>("/a");
  auto b = bus.advertise<std_msgs::Float64>("/b");
  std::vector<double> on_a;
  auto sub_a = bus.subscribe<std_msgs::Float64>("/a", [&](const std_msgs::Float64& msg) { on_a.push_back(msg.data); });
  auto sub_b = bus.subscribe<std_msgs::Float64>("/b", [&](const std_msgs::Float64& msg) { a.publish(msg); });
  b.publish(std_msgs::Float64{7.0});
  EXPECT_EQ(bus.flush(), 1u);  // /b's message; /a was visited before it was published
  EXPECT_TRUE(on_a.empty());
  EXPECT_EQ(bus.flush(), 1u);
  EXPECT_EQ(on_a, (std::vector<double>{7.0}));
  EXPECT_EQ(bus.flush(), 0u);

  // A typed subscriber that came before the publisher listens too.
  std::vector<double> early;
  auto sub_c = bus.subscribe<std_msgs::Float64>("/c", [&](const std_msgs::Float64& msg) { early.push_back(msg.data); });
  auto c = bus.advertise<std_msgs::Float64>("/c");
  c.publish(std_msgs::Float64{3.0});
  EXPECT_EQ(bus.flush(), 1u);
  EXPECT_EQ(early, (std::vector<double>{3.0}));
}

TEST(TopicBus, StalledSubscriberNeverBlocksThePublisherAndLaterSeesTheNewest) {
  TopicBus bus;
  auto publisher = bus.advertise<std_msgs::Float64>("/robot/ctrl/state");
  std::promise<void> entered;
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::mutex received_mutex;
  std::vector<double> received;
  auto subscription = bus.subscribe<std_msgs::Float64>("/robot/ctrl/state", [&](const std_msgs::Float64& msg) {
    {
      std::lock_guard lock(received_mutex);
      received.push_back(msg.data);
    }
    if (msg.data == 0.0) {
      entered.set_value();
      released.wait();  // the subscriber stalls on its first message
    }
  });
  bus.start(100us);

  ASSERT_TRUE(publisher.publish(std_msgs::Float64{0.0}));
  ASSERT_EQ(entered.get_future().wait_for(5s), std::future_status::ready);
  // The delivery thread is stuck in the callback; the publisher must go on.
  const auto start = std::chrono::steady_clock::now();
  for (int k = 1; k < 10000; ++k) publisher.publish(std_msgs::Float64{static_cast<double>(k)});
  const auto publishing_time = std::chrono::steady_clock::now() - start;
  release.set_value();
  bus.stop();  // delivers what is left
  bus.flush();

  EXPECT_LT(publishing_time, 2s);  // generous: it is ~10,000 copies of 8 bytes
  EXPECT_GT(publisher.droppedCount(), 0u);
  std::lock_guard lock(received_mutex);
  ASSERT_GE(received.size(), 2u);
  EXPECT_LE(received.size(), 1 + TopicBus::kDefaultQueueDepth + 1);
  EXPECT_EQ(received.back(), 9999.0);
  for (std::size_t i = 1; i < received.size(); ++i) EXPECT_LT(received[i - 1], received[i]) << "at " << i;
}

TEST(TopicBus, CommandInputHoldsTheLatestValue) {
  TopicBus bus;
  auto command = bus.commandInput<std_msgs::Float64>("/robot/ctrl/command");
  EXPECT_EQ(command.latest(), nullptr);
  EXPECT_FALSE(command.hasNewMessage());

  bus.publish("/robot/ctrl/command", std_msgs::Float64{2.0});
  EXPECT_TRUE(command.hasNewMessage());
  ASSERT_NE(command.latest(), nullptr);
  EXPECT_EQ(command.latest()->data, 2.0);
  EXPECT_FALSE(command.hasNewMessage());

  bus.publish("/robot/ctrl/command", std_msgs::Float64{3.0});
  bus.publish("/robot/ctrl/command", std_msgs::Float64{4.0});
  std_msgs::Float64 out;
  ASSERT_TRUE(command.readLatest(out));
  EXPECT_EQ(out.data, 4.0);
  EXPECT_EQ(command.latest()->data, 4.0);  // stays until something newer arrives

  command.clear();
  EXPECT_EQ(command.latest(), nullptr);
  EXPECT_FALSE(command.readLatest(out));
  servoloop::node::publishJson(bus, "/robot/ctrl/command", json::parse(R"({"data": 5})"));
  ASSERT_NE(command.latest(), nullptr);
  EXPECT_EQ(command.latest()->data, 5.0);
}

TEST(TopicBus, CommandInputReaderAlwaysSeesAWholeMessage) {
  constexpr std::size_t kWidth = 64;
  constexpr int kWrites = 20000;
  TopicBus bus;
  std_msgs::Float64MultiArray prototype;
  prototype.data.assign(kWidth, 0.0);
  auto command = bus.commandInput<std_msgs::Float64MultiArray>("/robot/group/command", prototype);

  std::atomic<bool> writing{true};
  std::thread writer([&] {
    std_msgs::Float64MultiArray msg = prototype;
    for (int k = 1; k <= kWrites; ++k) {
      std::fill(msg.data.begin(), msg.data.end(), static_cast<double>(k));
      bus.publish("/robot/group/command", msg);
    }
    writing = false;
  });

  std::size_t reads = 0;
  std::size_t torn = 0;
  double previous = 0.0;
  bool went_backwards = false;
  std::thread reader([&] {
    for (;;) {
      const bool last_round = !writing.load();
      if (const auto* msg = command.latest()) {
        ++reads;
        const double first = msg->data.front();
        if (msg->data.size() != kWidth ||
            std::any_of(msg->data.begin(), msg->data.end(), [first](double v) { return v != first; })) {
          ++torn;
        }
        if (first < previous) went_backwards = true;
        previous = first;
      }
      if (last_round) break;
    }
  });
  writer.join();
  reader.join();

  EXPECT_EQ(torn, 0u);
  EXPECT_FALSE(went_backwards);
  EXPECT_GT(reads, 0u);
  EXPECT_EQ(previous, static_cast<double>(kWrites));  // the newest value arrived
}

TEST(TopicBus, RealtimePublishersFeedCommandInputsOfTheSameTopic) {
  TopicBus bus;
  auto publisher = bus.advertise<std_msgs::Float64>("/robot/relay");
  auto input = bus.commandInput<std_msgs::Float64>("/robot/relay");
  publisher.publish(std_msgs::Float64{7.5});
  EXPECT_EQ(input.latest(), nullptr);  // not before the delivery pass
  bus.flush();
  ASSERT_NE(input.latest(), nullptr);
  EXPECT_EQ(input.latest()->data, 7.5);
}

TEST(TopicBus, JsonSubscriberMayComeBeforeTheTopicIsTyped) {
  TopicBus bus;
  std::vector<std::pair<double, json>> received;
  auto subscription = servoloop::node::subscribeJson(bus, "/robot/late", [&](Time stamp, const json& msg) {
    received.emplace_back(stamp.seconds, msg);
  });
  ASSERT_EQ(bus.list().size(), 1u);
  EXPECT_EQ(bus.list()[0].type, "");
  EXPECT_THAT(thrownMessage([&] { servoloop::node::publishJson(bus, "/robot/late", json{{"data", 1.0}}); }), HasSubstr("has no type yet"));

  auto publisher = bus.advertise<std_msgs::Float64>("/robot/late");
  EXPECT_EQ(bus.typeOf("/robot/late"), "std_msgs/Float64");
  bus.setTime(Time(2.0));
  publisher.publish(std_msgs::Float64{1.5});
  bus.flush();
  ASSERT_EQ(received.size(), 1u);
  EXPECT_EQ(received[0].first, 2.0);
  EXPECT_EQ(received[0].second, json::parse(R"({"data": 1.5})"));
}

TEST(TopicBus, PublishJsonChecksTheMessageAndNamesTopicAndField) {
  TopicBus bus;
  auto input = bus.commandInput<std_msgs::Float64MultiArray>("/robot/group/command");
  servoloop::node::publishJson(bus, "/robot/group/command", json::parse(R"({"data": [1, 2, 3]})"));
  ASSERT_NE(input.latest(), nullptr);
  EXPECT_EQ(input.latest()->data, (std::vector<double>{1.0, 2.0, 3.0}));

  EXPECT_EQ(thrownMessage([&] { servoloop::node::publishJson(bus, "/robot/group/command", json::parse(R"({"data": [1, "x"]})")); }),
            "topic '/robot/group/command': std_msgs/Float64MultiArray: field 'data[1]': expected a number, got "
            "string \"x\"");
  EXPECT_THAT(thrownMessage([&] { servoloop::node::publishJson(bus, "/robot/unknown", json{{"data", 1}}); }),
              HasSubstr("no topic '/robot/unknown'"));
  EXPECT_THAT(thrownMessage([&] { servoloop::node::publishJson(bus, "/robot/new", json{{"data", 1}}, "std_msgs/Float32"); }),
              HasSubstr("unknown message type 'std_msgs/Float32'"));

  // With a known type name the topic is created.
  std::vector<double> received;
  auto subscription = bus.subscribe<std_msgs::Float64>(
      "/robot/new", [&](const std_msgs::Float64& msg) { received.push_back(msg.data); });
  servoloop::node::publishJson(bus, "/robot/fresh", json{{"data", 1}}, "std_msgs/Float64");
  EXPECT_EQ(bus.typeOf("/robot/fresh"), "std_msgs/Float64");
  servoloop::node::publishJson(bus, "/robot/new", json(0.5), "std_msgs/Float64");
  bus.flush();
  EXPECT_EQ(received, (std::vector<double>{0.5}));
}

TEST(TopicBus, ListCountsPublishersAndSubscribers) {
  TopicBus bus;
  auto a = bus.advertise<std_msgs::Float64>("/b/state");
  auto b = bus.advertise<std_msgs::Float64>("/b/state");
  auto input = bus.commandInput<std_msgs::Float64MultiArray>("/a/command");
  auto typed = bus.subscribe<std_msgs::Float64>("/b/state", [](const auto&) {});
  auto any = servoloop::node::subscribeJson(bus, "/b/state", [](Time, const json&) {});

  auto topics = bus.list();
  ASSERT_EQ(topics.size(), 2u);
  EXPECT_EQ(topics[0].name, "/a/command");
  EXPECT_EQ(topics[0].type, "std_msgs/Float64MultiArray");
  EXPECT_EQ(topics[0].publishers, 0u);
  EXPECT_EQ(topics[0].subscribers, 1u);
  EXPECT_EQ(topics[1].name, "/b/state");
  EXPECT_EQ(topics[1].publishers, 2u);
  EXPECT_EQ(topics[1].subscribers, 2u);

  b.reset();
  typed.reset();
  input.reset();
  topics = bus.list();
  EXPECT_EQ(topics[0].subscribers, 0u);
  EXPECT_EQ(topics[1].publishers, 1u);
  EXPECT_EQ(topics[1].subscribers, 1u);
  EXPECT_TRUE(bus.hasTopic("b/state"));
  EXPECT_THAT(thrownMessage([&] { bus.typeOf("/c"); }), HasSubstr("topics are: /a/command, /b/state"));
}

TEST(TopicBus, UnsubscribedCallbacksAreNotCalledAndClosedPublishersStillDeliver) {
  TopicBus bus;
  int calls = 0;
  std::vector<double> last_values;
  auto subscription = bus.subscribe<std_msgs::Float64>("/t", [&](const std_msgs::Float64&) { ++calls; });
  auto keeper = bus.subscribe<std_msgs::Float64>(
      "/t", [&](const std_msgs::Float64& msg) { last_values.push_back(msg.data); });
  {
    auto publisher = bus.advertise<std_msgs::Float64>("/t");
    publisher.publish(std_msgs::Float64{1.0});
    bus.flush();
    EXPECT_EQ(calls, 1);
    subscription.reset();
    EXPECT_FALSE(subscription.active());
    publisher.publish(std_msgs::Float64{2.0});
  }  // publisher gone with a message still queued
  bus.flush();
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(last_values, (std::vector<double>{1.0, 2.0}));
  EXPECT_EQ(bus.list()[0].publishers, 0u);
}

TEST(TopicBus, ThrowingCallbackDoesNotStopDelivery) {
  TopicBus bus;
  std::string flush_error;
  int good_calls = 0;
  auto bad = bus.subscribe<std_msgs::Float64>("/t", [&](const std_msgs::Float64&) {
    try {
      bus.flush();
    } catch (const Error& e) {
      flush_error = e.what();
    }
    throw std::runtime_error("subscriber failed on purpose");
  });
  auto good = bus.subscribe<std_msgs::Float64>("/t", [&](const std_msgs::Float64&) { ++good_calls; });
  bus.publish("/t", std_msgs::Float64{1.0});
  bus.publish("/t", std_msgs::Float64{2.0});
  EXPECT_EQ(bus.flush(), 2u);
  EXPECT_EQ(good_calls, 2);
  EXPECT_THAT(flush_error, HasSubstr("called from a subscriber callback"));
}

TEST(TopicBus, UnsubscribingInsideACallbackStopsFurtherCalls) {
  TopicBus bus;
  int calls = 0;
  Subscription subscription;
  subscription = bus.subscribe<std_msgs::Float64>("/t", [&](const std_msgs::Float64&) {
    ++calls;
    subscription.reset();
  });
  bus.publish("/t", std_msgs::Float64{1.0});
  bus.publish("/t", std_msgs::Float64{2.0});
  bus.flush();
  EXPECT_EQ(calls, 1);
}

TEST(TopicBus, HandlesOutliveTheBus) {
  RealtimePublisher<std_msgs::Float64> publisher;
  RealtimeSubscriber<std_msgs::Float64> input;
  Subscription subscription;
  {
    TopicBus bus;
    bus.start();
    publisher = bus.advertise<std_msgs::Float64>("/t");
    input = bus.commandInput<std_msgs::Float64>("/t");
    subscription = bus.subscribe<std_msgs::Float64>("/t", [](const std_msgs::Float64&) {});
  }
  EXPECT_TRUE(publisher.publish(std_msgs::Float64{1.0}));  // goes nowhere, harmlessly
  EXPECT_EQ(input.latest(), nullptr);
  subscription.reset();
  publisher.reset();
  input.reset();
  EXPECT_FALSE(publisher.valid());
  EXPECT_FALSE(publisher.trylock());
}

}  // namespace
}  // namespace servoloop::realtime
