// Fallback controllers: a controller that faults in update() (throws, returns
// an error, writes a non-finite command) has the controllers it names in
// `fallback_controllers` started in the same cycle; they are checked at load
// (loaded already, claiming nothing it does not) and cannot be unloaded
// before it.
#include <gtest/gtest.h>

#include "controller_manager_test_support.hpp"

namespace servoloop::controller_manager::testing {
namespace {

const char* kFallbackYaml = R"(
hold: {type: test_controllers/EffortController, joint: joint1, output: 1.5, record_events: false}
other_joint: {type: test_controllers/EffortController, joint: joint2, output: 2.0, record_events: false}
velocity_hold: {type: test_controllers/VelocityController, joint: joint1, output: 0.0, record_events: false}
throws: {type: test_controllers/EffortController, joint: joint1, output: 5.0, fail_in: update, fail_after: 3,
         record_events: false, fallback_controllers: [hold]}
errors: {type: test_controllers/EffortController, joint: joint1, output: 5.0, fail_in: update_error, fail_after: 3,
         record_events: false, fallback_controllers: [hold]}
writes_nan: {type: test_controllers/EffortController, joint: joint1, output: 5.0, fail_in: nan, fail_after: 3,
             record_events: false, fallback_controllers: [hold]}
healthy: {type: test_controllers/EffortController, joint: joint1, output: 5.0, record_events: false,
          fallback_controllers: [hold]}
wrong_joint: {type: test_controllers/EffortController, joint: joint1, fallback_controllers: [other_joint]}
wrong_interface: {type: test_controllers/EffortController, joint: joint1, fallback_controllers: [velocity_hold]}
missing: {type: test_controllers/EffortController, joint: joint1, fallback_controllers: [nobody]}
itself: {type: test_controllers/EffortController, joint: joint1, fallback_controllers: [itself]}
not_a_list: {type: test_controllers/EffortController, joint: joint1, fallback_controllers: {hold: 1}}
)";

class FallbackTest : public ::testing::TestWithParam<const char*> {
 protected:
  FallbackTest() : f(kFallbackYaml) {}
  ManagerFixture f;
};

// Three good updates (cycles 1-3 after the start), the fault in the fourth;
// the fallback starts in that cycle and updates from the next one on.
TEST_P(FallbackTest, FaultStartsTheFallbackInTheSameCycle) {
  const std::string name = GetParam();
  ASSERT_TRUE(f.manager.loadController("hold"));
  ASSERT_TRUE(f.manager.loadController(name));
  ASSERT_TRUE(f.switchNow({name}, {}));
  f.cycles_n(4);
  auto* faulty = f.get<EffortTestController>(name);
  auto* hold = f.get<EffortTestController>("hold");
  EXPECT_EQ(faulty->state(), ControllerState::failed);
  EXPECT_EQ(faulty->update_calls, 4);
  EXPECT_EQ(hold->state(), ControllerState::running);
  EXPECT_EQ(hold->starting_calls, 1);
  EXPECT_EQ(hold->update_calls, 0);                // started, not yet updated
  EXPECT_DOUBLE_EQ(f.hw.effort_command[0], 0.0);  // the faulty one's safe output this cycle
  f.cycles_n(6);
  EXPECT_EQ(hold->update_calls, 6);
  EXPECT_DOUBLE_EQ(f.hw.effort_command[0], 1.5);  // the fallback holds from the next cycle

  const std::vector<ControllerFault> faults = f.manager.processFaults();
  ASSERT_EQ(faults.size(), 1u);
  EXPECT_TRUE(contains(faults[0].message, "fallback controller(s) 'hold' started in the same cycle"))
      << faults[0].message;

  // The fallback is now an ordinary running controller: the user switches
  // back once the faulty controller is reloaded.
  ASSERT_TRUE(f.switchNow({}, {"hold"}));
  EXPECT_EQ(hold->state(), ControllerState::stopped);
}

INSTANTIATE_TEST_SUITE_P(EveryKindOfUpdateFault, FallbackTest, ::testing::Values("throws", "errors", "writes_nan"));

TEST(Fallback, AHealthyControllerNeverStartsItsFallback) {
  ManagerFixture f(kFallbackYaml);
  ASSERT_TRUE(f.manager.loadController("hold"));
  ASSERT_TRUE(f.manager.loadController("healthy"));
  ASSERT_TRUE(f.switchNow({"healthy"}, {}));
  f.cycles_n(100);
  EXPECT_EQ(f.get<EffortTestController>("hold")->starting_calls, 0);
  EXPECT_DOUBLE_EQ(f.hw.effort_command[0], 5.0);
  // A normal stop starts nothing either.
  ASSERT_TRUE(f.switchNow({}, {"healthy"}));
  f.cycles_n(5);
  EXPECT_EQ(f.get<EffortTestController>("hold")->starting_calls, 0);
}

TEST(Fallback, LoadChecksTheFallbacks) {
  ManagerFixture f(kFallbackYaml);
  ASSERT_TRUE(f.manager.loadController("hold"));
  ASSERT_TRUE(f.manager.loadController("other_joint"));
  ASSERT_TRUE(f.manager.loadController("velocity_hold"));
  const auto error = [&](const std::string& name) { return f.manager.loadController(name).message; };
  EXPECT_TRUE(contains(error("wrong_joint"), "claims 'joint2' through EffortJointInterface, which 'wrong_joint' does not"))
      << error("wrong_joint");
  EXPECT_TRUE(contains(error("wrong_interface"), "claims 'joint1' through VelocityJointInterface"))
      << error("wrong_interface");
  EXPECT_TRUE(contains(error("missing"), "fallback controller 'nobody'")) << error("missing");
  EXPECT_TRUE(contains(error("missing"), "is not loaded; load it first"));
  EXPECT_TRUE(contains(error("itself"), "names the controller itself")) << error("itself");
  EXPECT_TRUE(contains(error("not_a_list"), "/test_robot/not_a_list/fallback_controllers")) << error("not_a_list");
  EXPECT_EQ(f.manager.listControllers().size(), 3u);  // none of them loaded
}

TEST(Fallback, AFallbackIsUnloadedAfterItsController) {
  ManagerFixture f(kFallbackYaml);
  ASSERT_TRUE(f.manager.loadController("hold"));
  ASSERT_TRUE(f.manager.loadController("healthy"));
  const ServiceResult refused = f.manager.unloadController("hold");
  EXPECT_FALSE(refused);
  EXPECT_TRUE(contains(refused.message, "it is the fallback of 'healthy'; unload 'healthy' first")) << refused.message;
  ASSERT_TRUE(f.manager.unloadController("healthy"));
  EXPECT_TRUE(f.manager.unloadController("hold"));
}

// Switches from another thread race the faults and the fallback starts of
// a controller that faults three updates after every start, with the
// real-time thread spinning: each switch starts it again and stops the
// fallback. Every fault starts the fallback exactly once, a switch that
// collides with a fallback start is refused (never half done), and in the end
// the two never run together. (The ThreadSanitizer lane runs this test.)
TEST(Fallback, SwitchesRacingFaultsAndFallbackStarts) {
  ManagerFixture f(kFallbackYaml);
  eventLogEnabled() = false;
  ASSERT_TRUE(f.manager.loadController("hold"));
  ASSERT_TRUE(f.manager.loadController("errors"));
  auto* faulty = f.get<EffortTestController>("errors");
  auto* hold = f.get<EffortTestController>("hold");
  int switched = 0;
  {
    RealtimeThread realtime(f.manager, 0.001, /*spin=*/true);
    for (int i = 0; i < 300; ++i) {
      const ServiceResult result =
          f.manager.switchController(SwitchRequest{{"errors"}, {"hold"}, SwitchStrictness::BEST_EFFORT, false, 5.0});
      switched += result ? 1 : 0;
    }
    realtime.stop();
  }
  EXPECT_GT(switched, 150);  // most switches land between faults
  // After its first fault the test controller (it counts updates over its
  // whole life) faults in the first update after every start: each start
  // but a still running one ended in a fault, and each fault started the
  // fallback (which nothing else starts) once.
  const bool faulty_running = faulty->state() == ControllerState::running;
  EXPECT_EQ(hold->starting_calls, faulty->starting_calls - (faulty_running ? 1 : 0));
  EXPECT_EQ(faulty->update_calls, faulty->starting_calls + 3 - (faulty_running ? 1 : 0));
  EXPECT_FALSE(faulty_running && hold->state() == ControllerState::running);
  // And the manager still switches: it stops whichever of the two runs (the
  // last switch may have started the faulty one after its last update, the
  // real-time thread stopping before the update that faults).
  ASSERT_TRUE(f.switchNow({}, {faulty_running ? "errors" : "hold"}));
  EXPECT_NE(hold->state(), ControllerState::running);
  EXPECT_NE(faulty->state(), ControllerState::running);
}

}  // namespace
}  // namespace servoloop::controller_manager::testing
