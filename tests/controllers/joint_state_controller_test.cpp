// joint_state_controller/JointStateController: parameters, message contents
// and publish timing in control time.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "controller_test_support.hpp"
#include "servoloop/controllers/joint_state_controller/joint_state_controller.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::controllers {
namespace {

using testing::initController;
using testing::makeContext;
using testing::TestJointsHW;
using JointStateMsg = servoloop::sensor_msgs::JointState;

class JointStateControllerTest : public ::testing::Test {
 protected:
  JointStateControllerTest() : hw({"wrist", "elbow", "shoulder"}) {
    const double positions[] = {0.1, 0.2, 0.3};
    for (std::size_t i = 0; i < hw.names.size(); ++i) {
      hw.position[i] = positions[i];
      hw.velocity[i] = -1.0 * static_cast<double>(i + 1);
      hw.effort[i] = 10.0 * static_cast<double>(i + 1);
    }
    subscription = bus.subscribe<JointStateMsg>("/robot/joint_states",
                                               [this](const JointStateMsg& msg) { received.push_back(msg); });
  }

  // Runs updates first..last at 1 kHz (control time k·1 ms) and returns the
  // numbers of the updates that published.
  std::vector<int> runAt1kHz(JointStateController& controller, int first, int last) {
    return testing::updatesThatPublishAt1kHz(controller, bus, first, last);
  }

  servoloop::realtime::TopicBus bus;
  TestJointsHW hw;
  std::vector<JointStateMsg> received;
  servoloop::realtime::Subscription subscription;
};

TEST_F(JointStateControllerTest, MissingPublishRateNamesControllerAndKey) {
  JointStateController controller;
  std::vector<hardware_interface::InterfaceResources> claimed;
  try {
    controller.initRequest(&hw, makeContext("joint_state_controller", "{}", &bus), claimed);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'joint_state_controller'"), std::string::npos) << message;
    EXPECT_NE(message.find("robot/joint_state_controller/publish_rate"), std::string::npos) << message;
  }
}

TEST_F(JointStateControllerTest, PublishesFirstCycleThenEvery20thAt50HzOn1kHz) {
  JointStateController controller;
  initController(controller, hw, makeContext("jsc", "{publish_rate: 50}", &bus));
  controller.startRequest(Time(0.0));
  EXPECT_EQ(runAt1kHz(controller, 1, 100), (std::vector<int>{1, 21, 41, 61, 81}));
  ASSERT_EQ(received.size(), 5u);

  // Every joint of the interface, sorted by name, with the storage's values.
  const JointStateMsg& msg = received.front();
  EXPECT_EQ(msg.name, (std::vector<std::string>{"elbow", "shoulder", "wrist"}));
  EXPECT_EQ(msg.position, (std::vector<double>{0.2, 0.3, 0.1}));
  EXPECT_EQ(msg.velocity, (std::vector<double>{-2.0, -3.0, -1.0}));
  EXPECT_EQ(msg.effort, (std::vector<double>{20.0, 30.0, 10.0}));
  EXPECT_DOUBLE_EQ(msg.stamp, 0.001);
  EXPECT_DOUBLE_EQ(received[1].stamp, 0.021);

  // Values are read when publishing, not at init.
  hw.position[hw.index("elbow")] = 1.5;
  received.clear();
  EXPECT_EQ(runAt1kHz(controller, 101, 101), (std::vector<int>{101}));
  ASSERT_EQ(received.size(), 1u);
  EXPECT_DOUBLE_EQ(received[0].position[0], 1.5);
}

TEST_F(JointStateControllerTest, RestartPublishesInItsFirstCycleAgain) {
  JointStateController controller;
  initController(controller, hw, makeContext("jsc", "{publish_rate: 50}", &bus));
  controller.startRequest(Time(0.0));
  runAt1kHz(controller, 1, 5);
  controller.stopRequest(Time(0.005));
  controller.startRequest(Time(0.010));
  EXPECT_EQ(runAt1kHz(controller, 11, 40), (std::vector<int>{11, 31}));
}

// A rate of 0 loads and never publishes, as in ros_controllers; a negative
// one is refused naming the parameter and value.
TEST_F(JointStateControllerTest, ZeroRateNeverPublishesAndANegativeRateIsRefused) {
  {
    JointStateController controller;
    initController(controller, hw, makeContext("jsc", "{publish_rate: 0}", &bus));
    controller.startRequest(Time(0.0));
    EXPECT_TRUE(runAt1kHz(controller, 1, 50).empty());
  }
  JointStateController controller;
  std::vector<hardware_interface::InterfaceResources> claimed;
  try {
    controller.initRequest(&hw, makeContext("joint_state_controller", "{publish_rate: -100}", &bus), claimed);
    FAIL() << "expected ConfigError for publish_rate -100";
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("robot/joint_state_controller/publish_rate"), std::string::npos) << message;
    EXPECT_NE(message.find("is -100.0;"), std::string::npos) << message;
    EXPECT_NE(message.find("publish_rate: 50"), std::string::npos) << message;
  }
  EXPECT_TRUE(received.empty());
}

TEST_F(JointStateControllerTest, ExtraJointsAreAppendedWithTheirConstants) {
  JointStateController controller;
  initController(controller, hw,
                 makeContext("jsc",
                             "publish_rate: 10\n"
                             "extra_joints:\n"
                             "  - {name: finger, position: 0.5, velocity: -0.25, effort: 2.0}\n"
                             "  - {name: antenna}\n"
                             "  - {name: elbow, position: 9.0}\n",  // already published: skipped
                             &bus));
  EXPECT_EQ(controller.jointNames(),
            (std::vector<std::string>{"elbow", "shoulder", "wrist", "finger", "antenna"}));
  controller.startRequest(Time(0.0));
  runAt1kHz(controller, 1, 1);
  ASSERT_EQ(received.size(), 1u);
  const JointStateMsg& msg = received[0];
  ASSERT_EQ(msg.name.size(), 5u);
  EXPECT_EQ(msg.position, (std::vector<double>{0.2, 0.3, 0.1, 0.5, 0.0}));
  EXPECT_EQ(msg.velocity, (std::vector<double>{-2.0, -3.0, -1.0, -0.25, 0.0}));
  EXPECT_EQ(msg.effort, (std::vector<double>{20.0, 30.0, 10.0, 2.0, 0.0}));
}

TEST_F(JointStateControllerTest, ExtraJointWithoutNameIsAnError) {
  JointStateController controller;
  std::vector<hardware_interface::InterfaceResources> claimed;
  try {
    controller.initRequest(
        &hw, makeContext("jsc", "{publish_rate: 10, extra_joints: [{position: 1.0}]}", &bus), claimed);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("robot/jsc/extra_joints[0]"), std::string::npos) << e.what();
  }
}

TEST_F(JointStateControllerTest, ClaimsNoJoint) {
  JointStateController controller;
  std::vector<hardware_interface::InterfaceResources> claimed;
  ASSERT_TRUE(controller.initRequest(&hw, makeContext("jsc", "{publish_rate: 10}", &bus), claimed));
  for (const auto& resources : claimed) EXPECT_TRUE(resources.resources.empty());
}

}  // namespace
}  // namespace servoloop::controllers
