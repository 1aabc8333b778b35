// The ground-truth publisher on the real-time thread: 100,000 control updates
// publish nav_msgs/Odometry at 50 Hz without one allocation, and the messages
// carry the base state in the right frames (pose in the world, twist in the
// root link's axes).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "alloc_counter.hpp"
#include "servoloop/node/ground_truth_publisher.hpp"

namespace servoloop::node {
namespace {

// A simulated robot whose floating base turns about z at 0.5 rad/s while
// moving along world x at 2 m/s (orientation: yaw 90°).
class FloatingHardware final : public hardware_interface::SimulatedRobotHW {
 public:
  void init(const hardware_interface::HardwareInfo&) override {}
  ReturnType read(Time, Duration) override { return ReturnType::ok; }
  ReturnType write(Time, Duration) override { return ReturnType::ok; }
  Duration timeStep() const override { return Duration(0.001); }
  ReturnType step() override { return ReturnType::ok; }
  Time simTime() const override { return Time(0.0); }
  void reset() override {}
  void setEmergencyStop(bool) override {}
  bool readBaseGroundTruth(hardware_interface::BaseGroundTruth& out) const noexcept override {
    out.position[0] = 1.0;
    out.position[2] = 0.5;
    out.orientation[2] = std::sqrt(0.5);  // yaw +90°: the link's x axis is the world's y
    out.orientation[3] = std::sqrt(0.5);
    out.linear_velocity[0] = 2.0;  // world x
    out.angular_velocity[2] = 0.5;
    return true;
  }
};

TEST(GroundTruthPublisher, HundredThousandUpdatesAllocateNothingAndPublishAtTheRate) {
  FloatingHardware hardware;
  realtime::TopicBus bus;
  std::vector<nav_msgs::Odometry> received;
  auto subscription = bus.subscribe<nav_msgs::Odometry>(
      "/robot/ground_truth/odom", [&](const nav_msgs::Odometry& msg) { received.push_back(msg); });
  ASSERT_TRUE(GroundTruthPublisher::applies(hardware));
  GroundTruthPublisher publisher(hardware, bus, "/robot/ground_truth/odom", "base_link");

  constexpr int kUpdates = 100000;  // 100 s at 1 kHz
  // Counted in batches of 0.2 s (ten messages, within the publisher's
  // queue); the bus delivers between batches (delivery is the non-real-time
  // side and may allocate).
  constexpr int kBatch = 200;
  std::size_t allocations = 0;
  for (int batch = 0; batch < kUpdates / kBatch; ++batch) {
    {
      servoloop::testing::AllocationCounter counter;
      for (int i = batch * kBatch; i < (batch + 1) * kBatch; ++i) {
        publisher.afterUpdate(Time(i * 0.001), Duration(0.001));
      }
      allocations += counter.allocations();
    }
    bus.flush();
  }
  EXPECT_EQ(allocations, 0u);
  ASSERT_EQ(received.size(), 5000u);  // 50 Hz over 100 s
  const nav_msgs::Odometry& msg = received.back();
  EXPECT_NEAR(msg.stamp, 99.98, 1e-9);
  EXPECT_EQ(msg.frame_id, "world");
  EXPECT_EQ(msg.child_frame_id, "base_link");
  EXPECT_DOUBLE_EQ(msg.position.x, 1.0);
  EXPECT_DOUBLE_EQ(msg.position.z, 0.5);
  // World x velocity in the link's axes (rotated +90° about z): along −y.
  EXPECT_NEAR(msg.linear.x, 0.0, 1e-12);
  EXPECT_NEAR(msg.linear.y, -2.0, 1e-12);
  EXPECT_NEAR(msg.angular.z, 0.5, 1e-12);
}

}  // namespace
}  // namespace servoloop::node
