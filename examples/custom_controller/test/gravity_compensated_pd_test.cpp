// Loads my_controllers/GravityCompensatedPD the way servoloop's controller
// manager does — through the plugin loader, from the built library — and runs
// it on a one-joint test RobotHW. Expected efforts are worked out by hand in
// the comments (link of the seed robot: m = 1 kg, l = 0.5 m, g = 9.81 m/s²,
// so gravity_torque = m·g·l = 4.905 N·m).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "servoloop/controller_manager/controller_base.hpp"
#include "servoloop/controller_manager/controller_context.hpp"
#include "servoloop/plugin/plugin_loader.hpp"
#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/hardware_interface/robot_hw.hpp"
#include "servoloop/params/parameters_yaml.hpp"

namespace {

namespace cm = servoloop::controller_manager;
namespace hi = servoloop::hardware_interface;
using servoloop::Duration;
using servoloop::Time;

constexpr const char* kType = "my_controllers/GravityCompensatedPD";

// One joint, "joint1", with plain storage the test sets and reads directly.
class OneJointHW : public hi::RobotHW {
 public:
  OneJointHW() {
    const hi::JointStateHandle state("joint1", &position, &velocity, &effort);
    state_interface.registerHandle(state);
    effort_interface.registerHandle(hi::JointHandle(state, &effort_command));
    registerInterface(&state_interface);
    registerInterface(&effort_interface);
  }
  void init(const hi::HardwareInfo&) override {}
  servoloop::ReturnType read(Time, Duration) override { return servoloop::ReturnType::ok; }
  servoloop::ReturnType write(Time, Duration) override { return servoloop::ReturnType::ok; }

  double position = 0.0, velocity = 0.0, effort = 0.0;  // joint space: rad, rad/s, N·m
  double effort_command = 0.0;                           // N·m
  hi::JointStateInterface state_interface;
  hi::EffortJointInterface effort_interface;
};

class GravityCompensatedPDTest : public ::testing::Test {
 protected:
  // The build folder first; SERVOLOOP_PLUGIN_PATH and the installed plugin
  // folder follow, as in a running node.
  GravityCompensatedPDTest() : loader_(servoloop::plugin::pluginSearchPath({MY_CONTROLLERS_PLUGIN_BUILD_DIR})) {}

  cm::ControllerContext context(const std::string& params_yaml) {
    cm::ControllerContext ctx;
    ctx.name = "arm_pd";
    ctx.robot_namespace = "/robot";
    ctx.params = servoloop::params::parametersFromYaml(YAML::Load(params_yaml), "/robot/" + ctx.name);
    ctx.topics = &bus_;
    return ctx;
  }

  // Loads and initialises the controller as the manager's loadController does.
  servoloop::plugin::PluginPtr<cm::ControllerBase> load(const std::string& params_yaml) {
    auto controller = loader_.create<cm::ControllerBase>(kType);
    EXPECT_TRUE(controller->initRequest(&hw_, context(params_yaml), claimed_));
    return controller;
  }

  servoloop::plugin::PluginLoader loader_;
  servoloop::realtime::TopicBus bus_;
  OneJointHW hw_;
  std::vector<hi::InterfaceResources> claimed_;
};

const std::string kParams = "{joint: joint1, kp: 20.0, kd: 2.0, gravity_torque: 4.905}";

TEST_F(GravityCompensatedPDTest, PluginLoaderFindsTheTypeInTheBuiltLibrary) {
  const std::vector<servoloop::plugin::PluginTypeInfo> controllers = loader_.listTypes("controller");
  const auto it = std::find_if(controllers.begin(), controllers.end(),
                               [](const servoloop::plugin::PluginTypeInfo& info) { return info.type == kType; });
  ASSERT_NE(it, controllers.end()) << kType << " is not listed as a controller type";
  EXPECT_EQ(std::filesystem::canonical(it->library).parent_path(),
            std::filesystem::canonical(MY_CONTROLLERS_PLUGIN_BUILD_DIR));
}

TEST_F(GravityCompensatedPDTest, ClaimsItsJointOnTheEffortInterface) {
  auto controller = load(kParams);
  ASSERT_EQ(claimed_.size(), 1u);
  EXPECT_EQ(claimed_[0].hardware_interface, "EffortJointInterface");
  EXPECT_EQ(claimed_[0].resources, std::set<std::string>{"joint1"});
}

TEST_F(GravityCompensatedPDTest, HoldsItsStartPositionAgainstGravity) {
  hw_.position = 0.3;
  auto controller = load(kParams);
  ASSERT_TRUE(controller->startRequest(Time(0.0)));
  ASSERT_EQ(controller->updateRequest(Time(0.01), Duration(0.01)), servoloop::ReturnType::ok);
  // No command yet: setpoint = 0.3, so only gravity compensation acts:
  // −4.905·sin(0.3) = −4.905·0.2955202067 = −1.4495266137 N·m.
  EXPECT_NEAR(hw_.effort_command, -1.4495266137, 1e-9);
}

TEST_F(GravityCompensatedPDTest, TracksTheCommandTopicWithPdPlusGravityCompensation) {
  hw_.position = 0.3;
  auto controller = load(kParams);
  ASSERT_TRUE(controller->startRequest(Time(0.0)));
  ASSERT_TRUE(bus_.hasTopic("/robot/arm_pd/command"));
  bus_.publish("/robot/arm_pd/command", servoloop::std_msgs::Float64{1.0});
  hw_.velocity = 0.5;
  ASSERT_EQ(controller->updateRequest(Time(0.01), Duration(0.01)), servoloop::ReturnType::ok);
  // 20·(1.0 − 0.3) − 2·0.5 − 4.905·sin(0.3) = 14 − 1 − 1.4495266137 = 11.5504733863 N·m.
  EXPECT_NEAR(hw_.effort_command, 11.5504733863, 1e-9);
}

TEST_F(GravityCompensatedPDTest, ClampsTheEffortToMaxEffort) {
  auto controller = load("{joint: joint1, kp: 20.0, max_effort: 5.0}");
  ASSERT_TRUE(controller->startRequest(Time(0.0)));
  bus_.publish("/robot/arm_pd/command", servoloop::std_msgs::Float64{1.0});
  controller->updateRequest(Time(0.01), Duration(0.01));
  EXPECT_DOUBLE_EQ(hw_.effort_command, 5.0);  // 20·1.0 = 20 N·m, clamped
  bus_.publish("/robot/arm_pd/command", servoloop::std_msgs::Float64{-1.0});
  controller->updateRequest(Time(0.02), Duration(0.01));
  EXPECT_DOUBLE_EQ(hw_.effort_command, -5.0);
}

TEST_F(GravityCompensatedPDTest, AMissingParameterIsNamedWithItsPathAndTheFix) {
  auto controller = loader_.create<cm::ControllerBase>(kType);
  try {
    controller->initRequest(&hw_, context("{joint: joint1, kd: 2.0}"), claimed_);
    FAIL() << "init accepted parameters without kp";
  } catch (const servoloop::ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("parameter 'robot/arm_pd/kp' is missing; add 'kp: 20.0'"),
              std::string::npos)
        << error.what();
  }
  EXPECT_FALSE(controller->isInitialized());
}

TEST_F(GravityCompensatedPDTest, AnUnknownJointIsRefused) {
  auto controller = loader_.create<cm::ControllerBase>(kType);
  EXPECT_THROW(controller->initRequest(&hw_, context("{joint: elbow, kp: 1.0}"), claimed_),
               servoloop::UnknownHandleError);
}

TEST_F(GravityCompensatedPDTest, ANonFiniteReadingGivesANonFiniteCommandThatTheManagerMakesSafe) {
  auto controller = load(kParams);
  ASSERT_TRUE(controller->startRequest(Time(0.0)));
  hw_.position = std::nan("");
  controller->updateRequest(Time(0.01), Duration(0.01));
  // What the manager checks after every update, and does on a fault.
  ASSERT_EQ(controller->firstNonFiniteCommand(), 0u);
  controller->abortRequest();
  EXPECT_EQ(hw_.effort_command, 0.0);
  EXPECT_TRUE(controller->isFailed());
}

}  // namespace
