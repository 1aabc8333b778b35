// imu_sensor_controller/ImuSensorController: one topic per sensor, the
// readings and frame copied, "not measured" for what a sensor lacks,
// parameters, and publish timing in control time.
#include <array>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "controller_test_support.hpp"
#include "servoloop/controllers/imu_sensor_controller/imu_sensor_controller.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::controllers {
namespace {

using testing::initController;
using testing::makeContext;
using testing::TestSensorsHW;
using ImuMsg = servoloop::sensor_msgs::Imu;
using Covariance = std::array<double, 9>;

class ImuSensorControllerTest : public ::testing::Test {
 protected:
  ImuSensorControllerTest() {
    TestSensorsHW::ImuStorage& imu = hw.addImu("imu", "imu_link");
    imu.orientation = {0.0, 0.0, 0.6, 0.8};
    imu.orientation_covariance = {1e-3, 0, 0, 0, 1e-3, 0, 0, 0, 2e-3};
    imu.angular_velocity = {0.1, -0.2, 0.3};
    imu.angular_velocity_covariance = {1e-4, 0, 0, 0, 2e-4, 0, 0, 0, 3e-4};
    imu.linear_acceleration = {0.5, 0.0, 9.81};
    imu.linear_acceleration_covariance = {0.01, 0, 0, 0, 0.02, 0, 0, 0, 0.03};
    TestSensorsHW::ImuStorage& base = hw.addImu("base_imu", "base_link");
    base.linear_acceleration = {0.0, 0.0, 9.81};
    subscriptions.push_back(
        bus.subscribe<ImuMsg>("/robot/imu", [this](const ImuMsg& msg) { imu_received.push_back(msg); }));
    subscriptions.push_back(
        bus.subscribe<ImuMsg>("/robot/base_imu", [this](const ImuMsg& msg) { base_received.push_back(msg); }));
  }

  // Runs updates first..last at 1 kHz (control time k·1 ms) and returns the
  // numbers of the updates that published.
  std::vector<int> runAt1kHz(ImuSensorController& controller, int first, int last) {
    return testing::updatesThatPublishAt1kHz(controller, bus, first, last);
  }

  std::string initError(const std::string& name, const std::string& params_yaml) {
    ImuSensorController controller;
    std::vector<hardware_interface::InterfaceResources> claimed;
    try {
      controller.initRequest(&hw, makeContext(name, params_yaml, &bus), claimed);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "(no ConfigError)";
  }

  servoloop::realtime::TopicBus bus;
  TestSensorsHW hw;
  std::vector<ImuMsg> imu_received;
  std::vector<ImuMsg> base_received;
  std::vector<servoloop::realtime::Subscription> subscriptions;
};

TEST_F(ImuSensorControllerTest, PublishesEverySensorOnItsOwnTopicFirstCycleThenAt50Hz) {
  ImuSensorController controller;
  initController(controller, hw, makeContext("imu_sensor_controller", "{publish_rate: 50}", &bus));
  EXPECT_EQ(controller.sensorNames(), (std::vector<std::string>{"base_imu", "imu"}));
  EXPECT_EQ(controller.topics(), (std::vector<std::string>{"/robot/base_imu", "/robot/imu"}));
  EXPECT_EQ(bus.typeOf("/robot/imu"), "sensor_msgs/Imu");
  controller.startRequest(Time(0.0));
  // Two sensors: two messages per publishing update.
  EXPECT_EQ(runAt1kHz(controller, 1, 100), (std::vector<int>{1, 21, 41, 61, 81}));
  EXPECT_EQ(controller.publishedCount(), 10u);
  ASSERT_EQ(imu_received.size(), 5u);
  ASSERT_EQ(base_received.size(), 5u);

  const ImuMsg& msg = imu_received.front();
  EXPECT_DOUBLE_EQ(msg.stamp, 0.001);
  EXPECT_EQ(msg.frame_id, "imu_link");
  EXPECT_EQ(msg.orientation.z, 0.6);
  EXPECT_EQ(msg.orientation.w, 0.8);
  EXPECT_EQ(msg.orientation_covariance, (Covariance{1e-3, 0, 0, 0, 1e-3, 0, 0, 0, 2e-3}));
  EXPECT_EQ(msg.angular_velocity.x, 0.1);
  EXPECT_EQ(msg.angular_velocity.y, -0.2);
  EXPECT_EQ(msg.angular_velocity.z, 0.3);
  EXPECT_EQ(msg.angular_velocity_covariance, (Covariance{1e-4, 0, 0, 0, 2e-4, 0, 0, 0, 3e-4}));
  EXPECT_EQ(msg.linear_acceleration.x, 0.5);
  EXPECT_EQ(msg.linear_acceleration.z, 9.81);
  EXPECT_EQ(msg.linear_acceleration_covariance, (Covariance{0.01, 0, 0, 0, 0.02, 0, 0, 0, 0.03}));
  EXPECT_DOUBLE_EQ(imu_received[1].stamp, 0.021);

  EXPECT_EQ(base_received.front().frame_id, "base_link");
  EXPECT_EQ(base_received.front().orientation.w, 1.0);
  EXPECT_EQ(base_received.front().linear_acceleration.z, 9.81);

  // Readings are taken when publishing, not at init.
  hw.imus.front().angular_velocity[2] = -4.0;
  hw.imus.front().orientation = {1.0, 0.0, 0.0, 0.0};
  imu_received.clear();
  EXPECT_EQ(runAt1kHz(controller, 101, 101), (std::vector<int>{101}));
  ASSERT_EQ(imu_received.size(), 1u);
  EXPECT_EQ(imu_received[0].angular_velocity.z, -4.0);
  EXPECT_EQ(imu_received[0].orientation.x, 1.0);
  EXPECT_EQ(imu_received[0].orientation.w, 0.0);
}

TEST_F(ImuSensorControllerTest, RestartPublishesInItsFirstCycleAgain) {
  ImuSensorController controller;
  initController(controller, hw, makeContext("imu_sensor_controller", "{publish_rate: 50}", &bus));
  controller.startRequest(Time(0.0));
  runAt1kHz(controller, 1, 5);
  controller.stopRequest(Time(0.005));
  controller.startRequest(Time(0.010));
  EXPECT_EQ(runAt1kHz(controller, 11, 40), (std::vector<int>{11, 31}));
}

// ROS's Imu message: a value the sensor does not give is zero with element 0
// of its covariance -1; a value without its covariance has an all-zero one
// ("unknown").
TEST_F(ImuSensorControllerTest, WhatASensorDoesNotMeasureIsMarkedNotMeasured) {
  const std::array<double, 3> gyro_rate = {0.0, 0.0, 1.25};
  hardware_interface::ImuSensorHandle::Data gyro;
  gyro.name = "gyro";
  gyro.frame_id = "gyro_link";
  gyro.angular_velocity = gyro_rate.data();  // no covariance, no orientation, no acceleration
  hw.addImu(gyro);
  const std::array<double, 4> heading = {0.0, 0.0, 0.0, 1.0};
  hardware_interface::ImuSensorHandle::Data compass;
  compass.name = "compass";
  compass.orientation = heading.data();
  hw.addImu(compass);
  std::vector<ImuMsg> gyro_received;
  std::vector<ImuMsg> compass_received;
  auto gyro_sub = bus.subscribe<ImuMsg>("/robot/gyro", [&](const ImuMsg& m) { gyro_received.push_back(m); });
  auto compass_sub =
      bus.subscribe<ImuMsg>("/robot/compass", [&](const ImuMsg& m) { compass_received.push_back(m); });

  ImuSensorController controller;
  initController(controller, hw, makeContext("imu_sensor_controller", "{publish_rate: 10}", &bus));
  controller.startRequest(Time(0.0));
  runAt1kHz(controller, 1, 1);
  ASSERT_EQ(gyro_received.size(), 1u);
  const ImuMsg& msg = gyro_received[0];
  EXPECT_EQ(msg.frame_id, "gyro_link");
  EXPECT_EQ(msg.angular_velocity.z, 1.25);
  EXPECT_EQ(msg.angular_velocity_covariance, Covariance{});
  EXPECT_EQ(msg.orientation.x, 0.0);
  EXPECT_EQ(msg.orientation.w, 0.0);
  EXPECT_EQ(msg.orientation_covariance, (Covariance{-1.0, 0, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(msg.linear_acceleration.z, 0.0);
  EXPECT_EQ(msg.linear_acceleration_covariance, (Covariance{-1.0, 0, 0, 0, 0, 0, 0, 0, 0}));

  ASSERT_EQ(compass_received.size(), 1u);
  EXPECT_EQ(compass_received[0].frame_id, "");
  EXPECT_EQ(compass_received[0].orientation.w, 1.0);
  EXPECT_EQ(compass_received[0].orientation_covariance, Covariance{});
  EXPECT_EQ(compass_received[0].angular_velocity_covariance[0], -1.0);
  EXPECT_EQ(compass_received[0].linear_acceleration_covariance[0], -1.0);
}

TEST_F(ImuSensorControllerTest, PublishRateIsRequiredAndNotNegative) {
  std::string message = initError("imu_sensor_controller", "{}");
  EXPECT_NE(message.find("'imu_sensor_controller'"), std::string::npos) << message;
  EXPECT_NE(message.find("robot/imu_sensor_controller/publish_rate' is missing"), std::string::npos) << message;

  message = initError("imu_sensor_controller", "{publish_rate: -100}");
  EXPECT_NE(message.find("robot/imu_sensor_controller/publish_rate' is -100.0;"), std::string::npos) << message;
  EXPECT_NE(message.find("publish_rate: 50"), std::string::npos) << message;

  // 0 loads and never publishes, as in ros_controllers.
  ImuSensorController controller;
  initController(controller, hw, makeContext("imu_sensor_controller", "{publish_rate: 0}", &bus));
  controller.startRequest(Time(0.0));
  EXPECT_TRUE(runAt1kHz(controller, 1, 50).empty());
  EXPECT_TRUE(imu_received.empty());
}

TEST_F(ImuSensorControllerTest, ASensorNameThatIsNoTopicNameIsNamed) {
  hardware_interface::ImuSensorHandle::Data bad;
  bad.name = "imu 2";
  hw.addImu(bad);
  const std::string message = initError("imu_sensor_controller", "{publish_rate: 50}");
  EXPECT_NE(message.find("controller 'imu_sensor_controller': IMU sensor 'imu 2' cannot be a topic name "
                         "(invalid topic name '/robot/imu 2'"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("; rename the sensor"), std::string::npos) << message;
}

// Read-only: claims nothing, so two controllers may read the same sensors.
TEST_F(ImuSensorControllerTest, ClaimsNothing) {
  ImuSensorController first;
  ImuSensorController second;
  for (ImuSensorController* controller : {&first, &second}) {
    std::vector<hardware_interface::InterfaceResources> claimed;
    ASSERT_TRUE(controller->initRequest(&hw, makeContext("imu", "{publish_rate: 10}", &bus), claimed));
    for (const auto& resources : claimed) EXPECT_TRUE(resources.resources.empty());
  }
}

TEST(ImuSensorController, HardwareWithoutImusIsRefusedNamingTheInterface) {
  testing::TestJointsHW hw({"joint1"});
  ImuSensorController controller;
  std::vector<hardware_interface::InterfaceResources> claimed;
  try {
    controller.initRequest(&hw, makeContext("imu_sensor_controller", "{publish_rate: 50}", nullptr), claimed);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("ImuSensorInterface"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace servoloop::controllers
