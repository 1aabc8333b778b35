// The real-time side of the topic bus allocates nothing: publishing a
// JointState and reading command inputs, 100,000 times, while the delivery
// thread and a non-real-time writer work concurrently.
#include <atomic>
#include <cstdio>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "alloc_counter.hpp"
#include "servoloop/node/message_json.hpp"
#include "servoloop/realtime/topic_bus.hpp"

namespace servoloop::realtime {
namespace {

using servoloop::testing::AllocationCounter;

TEST(TopicBusAllocation, RealtimePublishAndCommandReadAllocateNothing) {
  constexpr int kCycles = 100000;
  TopicBus bus;

  sensor_msgs::JointState joint_states;
  joint_states.name = {"joint1", "joint2", "joint3"};
  joint_states.position.assign(3, 0.0);
  joint_states.velocity.assign(3, 0.0);
  joint_states.effort.assign(3, 0.0);
  auto state_publisher = bus.advertise<sensor_msgs::JointState>("/robot/joint_states", joint_states);
  auto copy_publisher = bus.advertise<sensor_msgs::JointState>("/robot/joint_states_copy", joint_states);

  std_msgs::Float64MultiArray group_prototype;
  group_prototype.data.assign(3, 0.0);
  auto group_command = bus.commandInput<std_msgs::Float64MultiArray>("/robot/group/command", group_prototype);
  auto command = bus.commandInput<std_msgs::Float64>("/robot/ctrl/command");

  // Somebody listens, so the delivery thread really copies and converts.
  std::atomic<std::size_t> delivered{0};
  auto subscription = bus.subscribe<sensor_msgs::JointState>(
      "/robot/joint_states", [&](const sensor_msgs::JointState&) { delivered.fetch_add(1); });
  auto json_subscription = servoloop::node::subscribeJson(bus, "/robot/joint_states_copy", [&](Time, const nlohmann::json&) {});
  bus.start(std::chrono::microseconds(200));

  std::atomic<bool> running{true};
  std::thread writer([&] {  // non-real-time commands arriving throughout
    std_msgs::Float64MultiArray msg = group_prototype;
    for (double k = 1.0; running.load(); k += 1.0) {
      msg.data.assign(3, k);
      bus.publish("/robot/group/command", msg);
      bus.publish("/robot/ctrl/command", std_msgs::Float64{k});
      std::this_thread::yield();
    }
  });

  std_msgs::Float64MultiArray group_out = group_prototype;
  std_msgs::Float64 command_out;
  double checksum = 0.0;
  std::size_t publish_failures = 0;
  std::size_t allocations = 0;
  std::size_t deallocations = 0;
  {
    AllocationCounter counter;  // counts this (the "real-time") thread only
    for (int cycle = 0; cycle < kCycles; ++cycle) {
      const double t = cycle * 0.001;
      bus.setTime(Time(t));
      if (state_publisher.trylock()) {
        auto& msg = state_publisher.msg();
        msg.stamp = t;
        for (std::size_t j = 0; j < 3; ++j) {
          msg.position[j] = t * static_cast<double>(j);
          msg.velocity[j] = static_cast<double>(j);
          msg.effort[j] = -t;
        }
        state_publisher.unlockAndPublish();
      } else {
        ++publish_failures;
      }
      joint_states.stamp = t;
      if (!copy_publisher.publish(joint_states)) ++publish_failures;

      if (const auto* latest = group_command.latest()) checksum += latest->data[0];
      if (group_command.readLatest(group_out)) checksum += group_out.data[2];
      if (command.readLatest(command_out)) checksum += command_out.data;
      if (command.hasNewMessage()) checksum += 1.0;
    }
    allocations = counter.allocations();
    deallocations = counter.deallocations();
    if (allocations != 0) AllocationCounter::printFirstCountedStack();
  }
  running = false;
  writer.join();
  bus.stop();

  EXPECT_EQ(allocations, 0u);
  EXPECT_EQ(deallocations, 0u);
  // A publish may fail while the delivery thread is held up (another
  // process taking the core): the message is dropped, the publisher goes on.
  // No slot may be lost by it: with the bus stopped and drained, the
  // publisher again takes as many messages as it has slots (queue depth + 1)
  // without dropping one.
  std::printf("publish failures during the run: %zu of %d\n", publish_failures, 2 * kCycles);
  const std::uint64_t dropped_before = copy_publisher.droppedCount();
  for (std::size_t k = 0; k <= TopicBus::kDefaultQueueDepth; ++k) {
    EXPECT_TRUE(copy_publisher.publish(joint_states)) << k;
  }
  EXPECT_EQ(copy_publisher.droppedCount(), dropped_before);
  EXPECT_GT(delivered.load(), 0u);  // the delivery thread was really working meanwhile
  EXPECT_GT(checksum, 0.0);         // and commands were really read
}

// The counter is live in this executable: the non-real-time publish path,
// which copies into a queue for subscribers, is seen allocating.
TEST(TopicBusAllocation, CounterSeesNonRealtimeAllocations) {
  TopicBus bus;
  auto subscription = bus.subscribe<std_msgs::Float64MultiArray>("/t", [](const std_msgs::Float64MultiArray&) {});
  std_msgs::Float64MultiArray msg;
  msg.data.assign(8, 1.0);
  AllocationCounter counter;
  bus.publish("/t", msg);
  EXPECT_GT(counter.allocations(), 0u);

  // And it kept the stack of the first one, which names the publish path.
  std::FILE* file = std::tmpfile();
  ASSERT_NE(file, nullptr);
  AllocationCounter::printFirstCountedStack(fileno(file));
  std::rewind(file);
  std::string printed;
  char buffer[4096];
  while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, file)) printed.append(buffer, n);
  std::fclose(file);
  EXPECT_NE(printed.find("stack of the first counted allocation"), std::string::npos) << printed;
  EXPECT_NE(printed.find("TopicBus"), std::string::npos) << printed;
}

}  // namespace
}  // namespace servoloop::realtime
