// force_torque_sensor_controller/ForceTorqueSensorController: one topic per
// sensor, the wrench and frame copied, parameters, and publish timing in
// control time.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "controller_test_support.hpp"
#include "servoloop/controllers/force_torque_sensor_controller/force_torque_sensor_controller.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::controllers {
namespace {

using testing::initController;
using testing::makeContext;
using testing::TestSensorsHW;
using WrenchMsg = servoloop::geometry_msgs::WrenchStamped;

class ForceTorqueSensorControllerTest : public ::testing::Test {
 protected:
  ForceTorqueSensorControllerTest() {
    TestSensorsHW::ForceTorqueStorage& wrist = hw.addForceTorque("wrist_ft", "wrist_ft_link");
    wrist.force = {1.5, -2.0, 9.81};
    wrist.torque = {0.0, 0.125, -0.5};
    TestSensorsHW::ForceTorqueStorage& ankle = hw.addForceTorque("ankle_ft", "foot");
    ankle.force = {0.0, 0.0, -300.0};
    subscriptions.push_back(
        bus.subscribe<WrenchMsg>("/robot/wrist_ft", [this](const WrenchMsg& msg) { wrist_received.push_back(msg); }));
    subscriptions.push_back(
        bus.subscribe<WrenchMsg>("/robot/ankle_ft", [this](const WrenchMsg& msg) { ankle_received.push_back(msg); }));
  }

  std::vector<int> runAt1kHz(ForceTorqueSensorController& controller, int first, int last) {
    return testing::updatesThatPublishAt1kHz(controller, bus, first, last);
  }

  servoloop::realtime::TopicBus bus;
  TestSensorsHW hw;
  std::vector<WrenchMsg> wrist_received;
  std::vector<WrenchMsg> ankle_received;
  std::vector<servoloop::realtime::Subscription> subscriptions;
};

TEST_F(ForceTorqueSensorControllerTest, PublishesEverySensorOnItsOwnTopicFirstCycleThenAt100Hz) {
  ForceTorqueSensorController controller;
  initController(controller, hw, makeContext("ft_sensor_controller", "{publish_rate: 100}", &bus));
  EXPECT_EQ(controller.sensorNames(), (std::vector<std::string>{"ankle_ft", "wrist_ft"}));
  EXPECT_EQ(controller.topics(), (std::vector<std::string>{"/robot/ankle_ft", "/robot/wrist_ft"}));
  EXPECT_EQ(bus.typeOf("/robot/wrist_ft"), "geometry_msgs/WrenchStamped");
  controller.startRequest(Time(0.0));
  EXPECT_EQ(runAt1kHz(controller, 1, 35), (std::vector<int>{1, 11, 21, 31}));
  EXPECT_EQ(controller.publishedCount(), 8u);
  ASSERT_EQ(wrist_received.size(), 4u);
  ASSERT_EQ(ankle_received.size(), 4u);

  const WrenchMsg& msg = wrist_received.front();
  EXPECT_DOUBLE_EQ(msg.stamp, 0.001);
  EXPECT_EQ(msg.frame_id, "wrist_ft_link");
  EXPECT_EQ(msg.wrench.force.x, 1.5);
  EXPECT_EQ(msg.wrench.force.y, -2.0);
  EXPECT_EQ(msg.wrench.force.z, 9.81);
  EXPECT_EQ(msg.wrench.torque.x, 0.0);
  EXPECT_EQ(msg.wrench.torque.y, 0.125);
  EXPECT_EQ(msg.wrench.torque.z, -0.5);
  EXPECT_DOUBLE_EQ(wrist_received[3].stamp, 0.031);
  EXPECT_EQ(ankle_received.front().frame_id, "foot");
  EXPECT_EQ(ankle_received.front().wrench.force.z, -300.0);

  // Readings are taken when publishing, not at init.
  hw.force_torques.front().torque[0] = 7.0;
  wrist_received.clear();
  controller.stopRequest(Time(0.035));
  controller.startRequest(Time(0.040));
  EXPECT_EQ(runAt1kHz(controller, 41, 41), (std::vector<int>{41}));
  ASSERT_EQ(wrist_received.size(), 1u);
  EXPECT_EQ(wrist_received[0].wrench.torque.x, 7.0);
}

TEST_F(ForceTorqueSensorControllerTest, PublishRateIsRequiredAndNotNegative) {
  for (const char* params : {"{}", "{publish_rate: -1}"}) {
    ForceTorqueSensorController controller;
    std::vector<hardware_interface::InterfaceResources> claimed;
    try {
      controller.initRequest(&hw, makeContext("ft_sensor_controller", params, &bus), claimed);
      ADD_FAILURE() << "expected ConfigError for " << params;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("controller 'ft_sensor_controller': parameter "
                                           "'robot/ft_sensor_controller/publish_rate' is "),
                std::string::npos)
          << e.what();
    }
  }
  ForceTorqueSensorController controller;
  initController(controller, hw, makeContext("ft_sensor_controller", "{publish_rate: 0}", &bus));
  controller.startRequest(Time(0.0));
  EXPECT_TRUE(runAt1kHz(controller, 1, 50).empty());
  EXPECT_TRUE(wrist_received.empty());
}

TEST_F(ForceTorqueSensorControllerTest, ClaimsNothing) {
  ForceTorqueSensorController controller;
  std::vector<hardware_interface::InterfaceResources> claimed;
  ASSERT_TRUE(controller.initRequest(&hw, makeContext("ft", "{publish_rate: 10}", &bus), claimed));
  for (const auto& resources : claimed) EXPECT_TRUE(resources.resources.empty());
}

}  // namespace
}  // namespace servoloop::controllers
