// ControllerManager load / unload / list / reload, against the rules of
// ros_control's controller manager (reference: "Controller lifecycle and the manager").
#include <gtest/gtest.h>

#include "controller_manager_test_support.hpp"

namespace servoloop::controller_manager::testing {
namespace {

const char* kLifecycleYaml = R"(
effort1: {type: test_controllers/EffortController, joint: joint1}
effort2: {type: test_controllers/EffortController, joint: joint2}
state: {type: test_controllers/StateController, joints: [joint1, joint2, joint3]}
multi: {type: test_controllers/MultiController, joint: joint3}
no_type: {joint: joint1}
bad_type: {type: nope/NoSuchController, joint: joint1}
throws: {type: test_controllers/EffortController, joint: joint1, fail_in: init}
says_no: {type: test_controllers/EffortController, joint: joint1, fail_in: init_false}
bad_joint: {type: test_controllers/EffortController, joint: elbow}
velocity: {type: test_controllers/VelocityController, joint: joint1}
)";

TEST(ControllerManagerLoad, LoadedControllerIsListedInitializedWithItsClaims) {
  ManagerFixture f(kLifecycleYaml);
  ASSERT_TRUE(f.manager.loadController("effort1"));
  ASSERT_TRUE(f.manager.loadController("multi"));
  const auto specs = f.manager.listControllers();
  ASSERT_EQ(specs.size(), 2u);
  EXPECT_EQ(specs[0].name, "effort1");
  EXPECT_EQ(specs[0].type, "test_controllers/EffortController");
  EXPECT_EQ(specs[0].state, ControllerState::initialized);
  ASSERT_EQ(specs[0].claimed_resources.size(), 1u);
  EXPECT_EQ(specs[0].claimed_resources[0].hardware_interface, "EffortJointInterface");
  EXPECT_EQ(specs[0].claimed_resources[0].resources, (std::set<std::string>{"joint1"}));
  EXPECT_EQ(specs[1].name, "multi");
  ASSERT_EQ(specs[1].claimed_resources.size(), 2u);
  EXPECT_EQ(specs[1].claimed_resources[0].resources, (std::set<std::string>{"joint3"}));
  EXPECT_EQ(specs[1].claimed_resources[1].hardware_interface, "JointStateInterface");
}

TEST(ControllerManagerLoad, ControllerSeesItsNameParamsAndTheManagerRate) {
  ManagerFixture f(kLifecycleYaml, 500.0);
  ASSERT_TRUE(f.manager.loadController("effort2"));
  auto* controller = f.get<EffortTestController>("effort2");
  ASSERT_NE(controller, nullptr);
  EXPECT_EQ(controller->behaviour.name, "effort2");
  EXPECT_EQ(controller->behaviour.joints, (std::vector<std::string>{"joint2"}));
  EXPECT_DOUBLE_EQ(controller->manager_rate_hz, 500.0);
}

TEST(ControllerManagerLoad, DuplicateNameFails) {
  ManagerFixture f(kLifecycleYaml);
  ASSERT_TRUE(f.manager.loadController("effort1"));
  const ServiceResult again = f.manager.loadController("effort1");
  EXPECT_FALSE(again);
  EXPECT_TRUE(contains(again.message, "'effort1'")) << again.message;
  EXPECT_TRUE(contains(again.message, "already loaded")) << again.message;
  EXPECT_EQ(f.manager.listControllers().size(), 1u);
}

TEST(ControllerManagerLoad, MissingTypeParameterNamesThePath) {
  ManagerFixture f(kLifecycleYaml);
  const ServiceResult result = f.manager.loadController("no_type");
  EXPECT_FALSE(result);
  EXPECT_TRUE(contains(result.message, "'/test_robot/no_type/type' is missing")) << result.message;

  const ServiceResult absent = f.manager.loadController("not_in_yaml");
  EXPECT_FALSE(absent);
  EXPECT_TRUE(contains(absent.message, "'/test_robot/not_in_yaml/type' is missing")) << absent.message;
  EXPECT_TRUE(f.manager.listControllers().empty());
}

TEST(ControllerManagerLoad, UnknownTypeIsNamedWithTheKnownTypes) {
  ManagerFixture f(kLifecycleYaml);
  const ServiceResult result = f.manager.loadController("bad_type");
  EXPECT_FALSE(result);
  EXPECT_TRUE(contains(result.message, "unknown controller type 'nope/NoSuchController'")) << result.message;
  EXPECT_TRUE(contains(result.message, "test_controllers/EffortController")) << result.message;
}

TEST(ControllerManagerLoad, InitExceptionIsAFailedLoadCarryingItsMessageAndTheManagerGoesOn) {
  ManagerFixture f(kLifecycleYaml);
  const int destroyed_before = EffortTestController::destroyed().load();
  const ServiceResult result = f.manager.loadController("throws");
  EXPECT_FALSE(result);
  EXPECT_TRUE(contains(result.message, "test controller 'throws' fails in init on purpose")) << result.message;
  EXPECT_EQ(EffortTestController::destroyed().load(), destroyed_before + 1);  // not kept
  EXPECT_TRUE(f.manager.listControllers().empty());
  // Nothing was left claimed, and the manager goes on loading.
  EXPECT_TRUE(f.hw.effort_interface.getClaims().empty());
  EXPECT_TRUE(f.manager.loadController("effort1"));
}

TEST(ControllerManagerLoad, InitReturningFalseOrBadJointOrMissingInterfaceFails) {
  ManagerFixture f(kLifecycleYaml, 1000.0, /*offer_velocity=*/false);
  const ServiceResult says_no = f.manager.loadController("says_no");
  EXPECT_FALSE(says_no);
  EXPECT_TRUE(contains(says_no.message, "init returned false")) << says_no.message;

  const ServiceResult bad_joint = f.manager.loadController("bad_joint");
  EXPECT_FALSE(bad_joint);
  EXPECT_TRUE(contains(bad_joint.message, "'elbow'")) << bad_joint.message;

  const ServiceResult velocity = f.manager.loadController("velocity");
  EXPECT_FALSE(velocity);
  EXPECT_TRUE(contains(velocity.message, "needs VelocityJointInterface")) << velocity.message;
  EXPECT_TRUE(f.manager.listControllers().empty());
}

TEST(ControllerManagerLoad, NonNumericUpdateRateFails) {
  ManagerFixture f("c: {type: test_controllers/EffortController, joint: joint1, update_rate: fast}");
  const ServiceResult result = f.manager.loadController("c");
  EXPECT_FALSE(result);
  EXPECT_TRUE(contains(result.message, "/test_robot/c/update_rate: expected a number")) << result.message;
}

// A negative or non-finite rate is no rate: refused before the controller is made.
TEST(ControllerManagerLoad, NegativeOrNonFiniteUpdateRateFails) {
  for (const char* rate : {"-100", ".nan", ".inf"}) {
    ManagerFixture f(std::string("c: {type: test_controllers/EffortController, joint: joint1, update_rate: ") + rate + "}");
    const ServiceResult result = f.manager.loadController("c");
    EXPECT_FALSE(result) << rate;
    EXPECT_TRUE(contains(result.message, "/test_robot/c/update_rate: expected a number")) << result.message;
    EXPECT_TRUE(f.manager.listControllers().empty());
  }
}

TEST(ControllerManagerUnload, UnknownOrRunningFailsStoppedIsDestroyed) {
  ManagerFixture f(kLifecycleYaml);
  EXPECT_FALSE(f.manager.unloadController("effort1"));
  ASSERT_TRUE(f.manager.loadController("effort1"));
  ASSERT_TRUE(f.switchNow({"effort1"}, {}));

  const ServiceResult running = f.manager.unloadController("effort1");
  EXPECT_FALSE(running);
  EXPECT_TRUE(contains(running.message, "it is running")) << running.message;

  ASSERT_TRUE(f.switchNow({}, {"effort1"}));
  const int destroyed_before = EffortTestController::destroyed().load();
  EXPECT_TRUE(f.manager.unloadController("effort1"));
  EXPECT_EQ(EffortTestController::destroyed().load(), destroyed_before + 1);
  EXPECT_TRUE(f.manager.listControllers().empty());
  EXPECT_EQ(f.manager.getController("effort1"), nullptr);
  f.cycles_n(3);  // the real-time list no longer holds it
  // The name may be loaded again.
  EXPECT_TRUE(f.manager.loadController("effort1"));
}

TEST(ControllerManagerList, TypesComeFromTheFactorySorted) {
  ManagerFixture f(kLifecycleYaml);
  const auto types = f.manager.listControllerTypes();
  EXPECT_EQ(types, (std::vector<std::string>{
                       "test_controllers/EffortController", "test_controllers/MultiController",
                       "test_controllers/PositionController", "test_controllers/StateController",
                       "test_controllers/VelocityController"}));
}

TEST(ControllerManagerReload, RefusesWhileLoadedUnlessForceKill) {
  ManagerFixture f(kLifecycleYaml);
  ASSERT_TRUE(f.manager.loadController("effort1"));
  ASSERT_TRUE(f.manager.loadController("state"));
  ASSERT_TRUE(f.switchNow({"effort1"}, {}));

  const ServiceResult refused = f.manager.reloadControllerLibraries(false);
  EXPECT_FALSE(refused);
  EXPECT_TRUE(contains(refused.message, "effort1, state")) << refused.message;
  EXPECT_EQ(f.factory->reloads, 0);
  EXPECT_EQ(f.manager.listControllers().size(), 2u);

  // force_kill stops the running one on the real-time thread, then unloads all.
  auto* effort1 = f.get<EffortTestController>("effort1");
  ASSERT_NE(effort1, nullptr);
  eventLog().clear();
  {
    RealtimeThread loop(f.manager, 0.001);
    EXPECT_TRUE(f.manager.reloadControllerLibraries(true));
  }
  EXPECT_EQ(f.factory->reloads, 1);
  EXPECT_TRUE(f.manager.listControllers().empty());
  EXPECT_TRUE(std::find(eventLog().begin(), eventLog().end(), "stopping:effort1") != eventLog().end());

  // With nothing loaded it just reloads.
  EXPECT_TRUE(f.manager.reloadControllerLibraries(false));
  EXPECT_EQ(f.factory->reloads, 2);
}

TEST(ControllerManager, RejectsNullHardwareOrFactory) {
  TestRobotHW hw;
  auto params = ControllerManager::lookupIn(YAML::Load("{}"));
  EXPECT_THROW(ControllerManager(nullptr, std::make_shared<CountingFactory>(), params), Error);
  EXPECT_THROW(ControllerManager(&hw, nullptr, params), Error);
  EXPECT_THROW(ControllerManager(&hw, std::make_shared<CountingFactory>(), params, {}, -1.0), ConfigError);
}

}  // namespace
}  // namespace servoloop::controller_manager::testing
