// Controller<T> and MultiInterfaceController<T...>: interfaces, claims, the
// recorded command handles, lifecycle requests and safe outputs.
#include "servoloop/params/parameters_yaml.hpp"
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "controller_manager_test_support.hpp"

namespace servoloop::controller_manager::testing {
namespace {

ControllerContext contextFor(const std::string& name, const std::string& yaml) {
  ControllerContext context;
  context.name = name;
  context.robot_namespace = "/test_robot";
  context.params = servoloop::params::parametersFromYaml(YAML::Load(yaml), "/test/controller");
  return context;
}

TEST(ControllerBase, StateNamesAreRosControls) {
  EXPECT_STREQ(toString(ControllerState::initialized), "initialized");
  EXPECT_STREQ(toString(ControllerState::running), "running");
  EXPECT_STREQ(toString(ControllerState::stopped), "stopped");
  EXPECT_STREQ(toString(ControllerState::failed), "failed");
  EXPECT_STREQ(ControllerBase::kPluginKind, "controller");
}

TEST(Controller, InitRecordsClaimsPerInterfaceAndCommandStorage) {
  TestRobotHW hw;
  EffortTestController controller;
  std::vector<hi::InterfaceResources> claimed;
  ASSERT_TRUE(controller.initRequest(&hw, contextFor("arm", "{joints: [joint3, joint1]}"), claimed));

  EXPECT_EQ(controller.state(), ControllerState::initialized);
  ASSERT_EQ(claimed.size(), 1u);
  EXPECT_EQ(claimed[0].hardware_interface, "EffortJointInterface");
  EXPECT_EQ(claimed[0].resources, (std::set<std::string>{"joint1", "joint3"}));
  // The interface's claim record is left clean for the next controller.
  EXPECT_TRUE(hw.effort_interface.getClaims().empty());

  // Claimed commands point at the hardware's own effort command storage.
  const auto& commands = controller.claimedCommands();
  ASSERT_EQ(commands.size(), 2u);
  EXPECT_EQ(commands[0].resource, "joint1");
  EXPECT_EQ(commands[0].command, &hw.effort_command[0]);
  EXPECT_EQ(commands[0].position, &hw.position[0]);
  EXPECT_EQ(commands[0].safe, SafeCommand::zero);
  EXPECT_EQ(commands[1].resource, "joint3");
  EXPECT_EQ(commands[1].command, &hw.effort_command[2]);
}

TEST(Controller, EarlierClaimsOnTheInterfaceAreNotCountedAsOurs) {
  TestRobotHW hw;
  hw.effort_interface.getHandle("joint2");  // someone else's leftover claim
  EffortTestController controller;
  std::vector<hi::InterfaceResources> claimed;
  ASSERT_TRUE(controller.initRequest(&hw, contextFor("arm", "{joint: joint1}"), claimed));
  ASSERT_EQ(claimed.size(), 1u);
  EXPECT_EQ(claimed[0].resources, (std::set<std::string>{"joint1"}));
}

TEST(Controller, StateInterfaceClaimsNothing) {
  TestRobotHW hw;
  StateTestController controller;
  std::vector<hi::InterfaceResources> claimed;
  ASSERT_TRUE(controller.initRequest(&hw, contextFor("state", "{joints: [joint1, joint2]}"), claimed));
  ASSERT_EQ(claimed.size(), 1u);
  EXPECT_EQ(claimed[0].hardware_interface, "JointStateInterface");
  EXPECT_TRUE(claimed[0].resources.empty());
  EXPECT_TRUE(controller.claimedCommands().empty());
}

TEST(Controller, MissingInterfaceIsNamedWithWhatTheHardwareOffers) {
  TestRobotHW hw(/*offer_velocity=*/false);
  VelocityTestController controller;
  std::vector<hi::InterfaceResources> claimed;
  try {
    controller.initRequest(&hw, contextFor("vel", "{joint: joint1}"), claimed);
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    EXPECT_TRUE(contains(message, "controller 'vel' needs VelocityJointInterface")) << message;
    EXPECT_TRUE(contains(message, "EffortJointInterface")) << message;
    EXPECT_TRUE(contains(message, "PositionJointInterface")) << message;
  }
  EXPECT_EQ(controller.state(), ControllerState::constructed);
}

TEST(Controller, UnknownJointFailsInitAndLeavesNoClaims) {
  TestRobotHW hw;
  EffortTestController controller;
  std::vector<hi::InterfaceResources> claimed;
  EXPECT_THROW(controller.initRequest(&hw, contextFor("arm", "{joints: [joint1, elbow]}"), claimed),
               UnknownHandleError);
  EXPECT_TRUE(hw.effort_interface.getClaims().empty());
  EXPECT_EQ(controller.state(), ControllerState::constructed);
}

TEST(Controller, InitReturningFalseLeavesItConstructed) {
  TestRobotHW hw;
  EffortTestController controller;
  std::vector<hi::InterfaceResources> claimed;
  EXPECT_FALSE(controller.initRequest(&hw, contextFor("arm", "{joint: joint1, fail_in: init_false}"),
                                      claimed));
  EXPECT_EQ(controller.state(), ControllerState::constructed);
}

TEST(Controller, PositionCommandsHoldTheMeasuredPosition) {
  TestRobotHW hw;
  PositionTestController controller;
  std::vector<hi::InterfaceResources> claimed;
  ASSERT_TRUE(controller.initRequest(&hw, contextFor("pos", "{joint: joint2}"), claimed));
  ASSERT_EQ(controller.claimedCommands().size(), 1u);
  EXPECT_EQ(controller.claimedCommands()[0].safe, SafeCommand::hold_position);

  hw.position_command[1] = 3.0;
  hw.position[1] = -0.75;
  controller.writeSafeCommands();
  EXPECT_DOUBLE_EQ(hw.position_command[1], -0.75);

  // With a broken measurement a finite last command is kept, a NaN one zeroed.
  hw.position[1] = std::numeric_limits<double>::quiet_NaN();
  hw.position_command[1] = 0.5;
  controller.writeSafeCommands();
  EXPECT_DOUBLE_EQ(hw.position_command[1], 0.5);
  hw.position_command[1] = std::numeric_limits<double>::infinity();
  controller.writeSafeCommands();
  EXPECT_DOUBLE_EQ(hw.position_command[1], 0.0);
}

TEST(Controller, LifecycleRequestsFollowRosControlStates) {
  TestRobotHW hw;
  EffortTestController controller;
  EXPECT_FALSE(controller.startRequest(Time(0.0)));  // not initialised
  std::vector<hi::InterfaceResources> claimed;
  ASSERT_TRUE(controller.initRequest(&hw, contextFor("arm", "{joint: joint1, output: 4.0, record_events: false}"),
                                     claimed));
  EXPECT_THROW(controller.initRequest(&hw, contextFor("arm", "{joint: joint1}"), claimed), Error);

  EXPECT_FALSE(controller.stopRequest(Time(0.0)));  // not running
  EXPECT_TRUE(controller.startRequest(Time(1.0)));
  EXPECT_EQ(controller.state(), ControllerState::running);
  EXPECT_EQ(controller.starting_calls, 1);
  EXPECT_FALSE(controller.startRequest(Time(1.0)));  // already running
  EXPECT_EQ(controller.updateRequest(Time(1.1), Duration(0.1)), ReturnType::ok);
  EXPECT_DOUBLE_EQ(hw.effort_command[0], 4.0);
  EXPECT_EQ(controller.firstNonFiniteCommand(), ControllerBase::kAllCommandsFinite);

  hw.effort_command[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(controller.firstNonFiniteCommand(), 0u);
  controller.abortRequest();
  EXPECT_EQ(controller.state(), ControllerState::failed);
  EXPECT_EQ(controller.safe_output_calls, 1);
  EXPECT_DOUBLE_EQ(hw.effort_command[0], 0.0);

  EXPECT_TRUE(controller.startRequest(Time(2.0)));  // a failed controller may be restarted
  EXPECT_TRUE(controller.stopRequest(Time(3.0)));
  EXPECT_EQ(controller.state(), ControllerState::stopped);
  EXPECT_EQ(controller.stopping_calls, 1);
}

TEST(MultiInterfaceController, InitSeesOnlyItsInterfacesAndClaimsArePerInterface) {
  TestRobotHW hw;
  MultiTestController controller;
  std::vector<hi::InterfaceResources> claimed;
  ASSERT_TRUE(controller.initRequest(&hw, contextFor("multi", "{joint: joint2}"), claimed));
  EXPECT_FALSE(controller.saw_velocity_interface);
  ASSERT_EQ(claimed.size(), 2u);
  EXPECT_EQ(claimed[0].hardware_interface, "EffortJointInterface");
  EXPECT_EQ(claimed[0].resources, (std::set<std::string>{"joint2"}));
  EXPECT_EQ(claimed[1].hardware_interface, "JointStateInterface");
  EXPECT_TRUE(claimed[1].resources.empty());
  ASSERT_EQ(controller.claimedCommands().size(), 1u);
  EXPECT_EQ(controller.claimedCommands()[0].command, &hw.effort_command[1]);
  EXPECT_TRUE(hw.effort_interface.getClaims().empty());
}

class VelocityAndEffort
    : public MultiInterfaceController<hi::VelocityJointInterface, hi::EffortJointInterface> {
 public:
  explicit VelocityAndEffort(bool optional) : MultiInterfaceController(optional) {}
  bool init(hi::RobotHW* hw, const ControllerContext&) override {
    had_velocity = hw->get<hi::VelocityJointInterface>() != nullptr;
    hw->get<hi::EffortJointInterface>()->getHandle("joint1");
    return true;
  }
  ReturnType update(const Time&, const Duration&) override { return ReturnType::ok; }
  bool had_velocity = true;
};

TEST(MultiInterfaceController, MissingRequiredInterfaceFailsOptionalOneIsLeftOut) {
  TestRobotHW hw(/*offer_velocity=*/false);
  std::vector<hi::InterfaceResources> claimed;
  VelocityAndEffort required(false);
  try {
    required.initRequest(&hw, contextFor("both", "{}"), claimed);
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_TRUE(contains(e.what(), "controller 'both' needs VelocityJointInterface")) << e.what();
  }

  VelocityAndEffort optional(true);
  ASSERT_TRUE(optional.initRequest(&hw, contextFor("both", "{}"), claimed));
  EXPECT_FALSE(optional.had_velocity);
  ASSERT_EQ(claimed.size(), 1u);
  EXPECT_EQ(claimed[0].hardware_interface, "EffortJointInterface");
}

}  // namespace
}  // namespace servoloop::controller_manager::testing
