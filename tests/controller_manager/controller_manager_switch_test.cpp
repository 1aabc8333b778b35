// ControllerManager::switchController: ros_control's STRICT / BEST_EFFORT
// rules, resource conflicts, the hardware's say, the order of a switch on the
// real-time thread, and switching from another thread while the loop runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include "controller_manager_test_support.hpp"

namespace servoloop::controller_manager::testing {
namespace {

const char* kSwitchYaml = R"(
a: {type: test_controllers/EffortController, joint: joint1, output: 1.0}
b: {type: test_controllers/EffortController, joint: joint2, output: 2.0}
a_too: {type: test_controllers/EffortController, joint: joint1, output: 3.0}
state: {type: test_controllers/StateController, joints: [joint1, joint2, joint3]}
quitter: {type: test_controllers/EffortController, joint: joint3, fail_in: deactivate, fail_after: 2}
)";

class SwitchTest : public ::testing::Test {
 protected:
  SwitchTest() : f(kSwitchYaml) {}
  void SetUp() override {
    for (const char* name : {"a", "b", "a_too", "state", "quitter"}) {
      ASSERT_TRUE(f.manager.loadController(name)) << name;
    }
  }
  ControllerState stateOf(const std::string& name) { return f.manager.getController(name)->state(); }
  EffortTestController* effort(const std::string& name) { return f.get<EffortTestController>(name); }

  ManagerFixture f;
};

TEST_F(SwitchTest, StartingRunsInTheSwitchCycleAndTheFirstUpdateComesInTheNext) {
  ASSERT_TRUE(f.manager.requestSwitch(SwitchRequest{{"a"}, {}, SwitchStrictness::STRICT, false, 0}));
  EXPECT_TRUE(f.manager.switchPending());
  EXPECT_EQ(effort("a")->starting_calls, 0);  // nothing happens off the real-time thread

  f.cycle();  // t = 0.001: the switch
  EXPECT_FALSE(f.manager.switchPending());
  EXPECT_EQ(stateOf("a"), ControllerState::running);
  EXPECT_EQ(effort("a")->starting_calls, 1);
  EXPECT_DOUBLE_EQ(effort("a")->starting_time.seconds, 0.001);
  EXPECT_EQ(effort("a")->update_calls, 0);

  f.cycle();  // t = 0.002: first update, period since starting
  EXPECT_EQ(effort("a")->update_calls, 1);
  ASSERT_EQ(effort("a")->periods.size(), 1u);
  EXPECT_NEAR(effort("a")->periods[0], 0.001, 1e-12);
  EXPECT_DOUBLE_EQ(f.hw.effort_command[0], 1.0);
  EXPECT_EQ(eventLog(), (std::vector<std::string>{"doSwitch", "starting:a", "update:a"}));
}

// As in ros_control: the hardware changes its modes first, so that when it
// cannot, nothing else has changed.
TEST_F(SwitchTest, HardwareFirstThenStopListThenStartList) {
  ASSERT_TRUE(f.switchNow({"a"}, {}));
  f.cycle();
  eventLog().clear();
  ASSERT_TRUE(f.switchNow({"a_too"}, {"a"}));
  EXPECT_EQ(eventLog(), (std::vector<std::string>{"doSwitch", "stopping:a", "starting:a_too"}));
  EXPECT_EQ(f.hw.do_switch_start_count, 1u);
  EXPECT_EQ(f.hw.do_switch_stop_count, 1u);
  ASSERT_EQ(f.hw.last_prepare_start.size(), 1u);
  EXPECT_EQ(f.hw.last_prepare_start[0].name, "a_too");
  ASSERT_EQ(f.hw.last_prepare_start[0].claimed_resources.size(), 1u);
  EXPECT_EQ(f.hw.last_prepare_start[0].claimed_resources[0].resources, (std::set<std::string>{"joint1"}));
  ASSERT_EQ(f.hw.last_prepare_stop.size(), 1u);
  EXPECT_EQ(f.hw.last_prepare_stop[0].name, "a");
  EXPECT_EQ(stateOf("a"), ControllerState::stopped);
  EXPECT_EQ(stateOf("a_too"), ControllerState::running);
}

// A hardware that cannot change its command modes (doSwitch returns an error
// or throws) aborts the whole switch: the running controller runs on, nothing
// stops or starts, and the switch fails naming why.
TEST_F(SwitchTest, AFailedModeSwitchAbortsTheWholeSwitch) {
  for (const bool throws : {false, true}) {
    SCOPED_TRACE(throws ? "doSwitch throws" : "doSwitch returns an error");
    ManagerFixture g(kSwitchYaml);
    ASSERT_TRUE(g.manager.loadController("a"));
    ASSERT_TRUE(g.manager.loadController("a_too"));
    ASSERT_TRUE(g.switchNow({"a"}, {}));
    ASSERT_TRUE(g.manager.finishSwitch());
    g.cycle();
    EXPECT_DOUBLE_EQ(g.hw.effort_command[0], 1.0);

    g.hw.do_switch_result = ReturnType::error;
    g.hw.do_switch_throws = throws;
    eventLog().clear();
    ASSERT_TRUE(g.switchNow({"a_too"}, {"a"}));  // accepted by prepareSwitch, carried out in the cycle
    EXPECT_FALSE(g.manager.switchPending());
    const ServiceResult result = g.manager.finishSwitch();
    EXPECT_FALSE(result);
    EXPECT_TRUE(contains(result.message, "could not change its command modes for start [a_too], stop [a]"))
        << result.message;
    EXPECT_TRUE(contains(result.message, throws ? "RobotHW::doSwitch threw: drive 3 did not answer the mode change"
                                                : "RobotHW::doSwitch returned an error"))
        << result.message;
    EXPECT_TRUE(contains(result.message, "nothing was switched")) << result.message;
    // No stopping(), no starting(): a updates on in the same cycle.
    EXPECT_EQ(eventLog(), (std::vector<std::string>{"doSwitch", "update:a"}));
    EXPECT_EQ(g.manager.getController("a")->state(), ControllerState::running);
    EXPECT_EQ(g.manager.getController("a_too")->state(), ControllerState::initialized);
    g.cycle();
    EXPECT_DOUBLE_EQ(g.hw.effort_command[0], 1.0);  // a still commands

    // The hardware recovers: the same switch goes through.
    g.hw.do_switch_result = ReturnType::ok;
    g.hw.do_switch_throws = false;
    ASSERT_TRUE(g.switchNow({"a_too"}, {"a"}));
    EXPECT_TRUE(g.manager.finishSwitch());
    g.cycle();
    EXPECT_EQ(g.manager.getController("a_too")->state(), ControllerState::running);
    EXPECT_DOUBLE_EQ(g.hw.effort_command[0], 3.0);
  }
}

// The blocking switch (what `servoloop control switch` and the spawner use)
// returns the same failure while the loop runs on another thread.
TEST_F(SwitchTest, ABlockingSwitchReportsTheFailedModeSwitch) {
  ASSERT_TRUE(f.switchNow({"a"}, {}));
  f.hw.do_switch_result = ReturnType::error;
  std::atomic<bool> stop{false};
  std::thread loop([&] {
    while (!stop.load()) {
      f.cycle();
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  });
  const ServiceResult result = f.manager.switchController({"a_too"}, {"a"}, SwitchStrictness::STRICT);
  stop.store(true);
  loop.join();
  EXPECT_FALSE(result);
  EXPECT_TRUE(contains(result.message, "RobotHW::doSwitch returned an error")) << result.message;
  EXPECT_EQ(stateOf("a"), ControllerState::running);
  EXPECT_EQ(stateOf("a_too"), ControllerState::initialized);
}

TEST_F(SwitchTest, StrictFailsOnAnUnknownNameBestEffortDropsIt) {
  const ServiceResult strict = f.switchNow({"a", "ghost"}, {}, SwitchStrictness::STRICT);
  EXPECT_FALSE(strict);
  EXPECT_TRUE(contains(strict.message, "could not start controller 'ghost'")) << strict.message;
  EXPECT_EQ(stateOf("a"), ControllerState::initialized);  // nothing switched
  EXPECT_EQ(f.hw.prepare_calls, 0);

  EXPECT_TRUE(f.switchNow({"a", "ghost"}, {"phantom"}, SwitchStrictness::BEST_EFFORT));
  EXPECT_EQ(stateOf("a"), ControllerState::running);
}

TEST_F(SwitchTest, StrictFailsStoppingANonRunningControllerBestEffortDropsIt) {
  const ServiceResult strict = f.switchNow({"a"}, {"b"}, SwitchStrictness::STRICT);
  EXPECT_FALSE(strict);
  EXPECT_TRUE(contains(strict.message, "could not stop controller 'b': it is not running")) << strict.message;
  EXPECT_EQ(stateOf("a"), ControllerState::initialized);

  EXPECT_TRUE(f.switchNow({"a"}, {"b"}, SwitchStrictness::BEST_EFFORT));
  EXPECT_EQ(stateOf("a"), ControllerState::running);
  EXPECT_EQ(effort("b")->stopping_calls, 0);
}

TEST_F(SwitchTest, StrictFailsStartingARunningControllerBestEffortDropsIt) {
  ASSERT_TRUE(f.switchNow({"a"}, {}));
  const ServiceResult strict = f.switchNow({"a", "b"}, {}, SwitchStrictness::STRICT);
  EXPECT_FALSE(strict);
  EXPECT_TRUE(contains(strict.message, "could not start controller 'a': it is already running")) << strict.message;
  EXPECT_EQ(stateOf("b"), ControllerState::initialized);

  EXPECT_TRUE(f.switchNow({"a", "b"}, {}, SwitchStrictness::BEST_EFFORT));
  EXPECT_EQ(stateOf("b"), ControllerState::running);
  EXPECT_EQ(effort("a")->starting_calls, 1);  // not started twice
}

TEST_F(SwitchTest, BestEffortWithEverythingDroppedIsANoOp) {
  const int prepare_before = f.hw.prepare_calls;
  EXPECT_TRUE(f.manager.requestSwitch(
      SwitchRequest{{"ghost"}, {"b"}, SwitchStrictness::BEST_EFFORT, false, 0}));
  EXPECT_FALSE(f.manager.switchPending());
  EXPECT_EQ(f.hw.prepare_calls, prepare_before);
}

TEST_F(SwitchTest, SameNameInBothListsIsAnErrorWhateverTheStrictness) {
  ASSERT_TRUE(f.switchNow({"a"}, {}));
  for (auto strictness : {SwitchStrictness::STRICT, SwitchStrictness::BEST_EFFORT}) {
    const ServiceResult result = f.switchNow({"a"}, {"a"}, strictness);
    EXPECT_FALSE(result);
    EXPECT_TRUE(contains(result.message, "'a' is in both the start and the stop list")) << result.message;
  }
  EXPECT_EQ(effort("a")->stopping_calls, 0);
  EXPECT_EQ(stateOf("a"), ControllerState::running);
}

TEST_F(SwitchTest, ConflictingClaimsOnTheResultingSetAreRefused) {
  // Both at once.
  const ServiceResult both = f.switchNow({"a", "a_too"}, {});
  EXPECT_FALSE(both);
  EXPECT_TRUE(contains(both.message, "'joint1' is claimed by 'a' and 'a_too'")) << both.message;
  EXPECT_EQ(stateOf("a"), ControllerState::initialized);

  // One running, the other started.
  ASSERT_TRUE(f.switchNow({"a"}, {}));
  const ServiceResult onto_running = f.switchNow({"a_too"}, {});
  EXPECT_FALSE(onto_running);
  EXPECT_TRUE(contains(onto_running.message, "'joint1'")) << onto_running.message;
  EXPECT_EQ(stateOf("a_too"), ControllerState::initialized);

  // Stopping the owner in the same switch resolves it (running - stop + start).
  EXPECT_TRUE(f.switchNow({"a_too"}, {"a"}));
  EXPECT_EQ(stateOf("a_too"), ControllerState::running);
}

TEST_F(SwitchTest, StateInterfaceReadersDoNotConflict) {
  EXPECT_TRUE(f.switchNow({"a", "b", "state"}, {}));
  EXPECT_EQ(stateOf("state"), ControllerState::running);
}

TEST_F(SwitchTest, HardwareRefusalInPrepareSwitchFailsAndNothingIsPending) {
  f.hw.accept_switch = false;
  const ServiceResult result = f.switchNow({"a"}, {});
  EXPECT_FALSE(result);
  EXPECT_TRUE(contains(result.message, "the hardware refused the switch")) << result.message;
  EXPECT_FALSE(f.manager.switchPending());
  f.cycles_n(2);
  EXPECT_EQ(stateOf("a"), ControllerState::initialized);
  EXPECT_EQ(f.hw.do_switch_calls.load(), 0);
}

TEST_F(SwitchTest, ASecondRequestWhileOneIsPendingIsRefused) {
  ASSERT_TRUE(f.manager.requestSwitch(SwitchRequest{{"a"}, {}, SwitchStrictness::STRICT, false, 0}));
  const ServiceResult second = f.manager.requestSwitch(SwitchRequest{{"b"}, {}, SwitchStrictness::STRICT, false, 0});
  EXPECT_FALSE(second);
  EXPECT_TRUE(contains(second.message, "still waiting")) << second.message;
  const ServiceResult unload = f.manager.unloadController("b");
  EXPECT_FALSE(unload);
  f.cycle();
  EXPECT_EQ(stateOf("a"), ControllerState::running);
  EXPECT_EQ(stateOf("b"), ControllerState::initialized);
}

TEST_F(SwitchTest, DeactivateStopsCleanlyWithoutAFault) {
  ASSERT_TRUE(f.switchNow({"quitter"}, {}));
  f.cycles_n(5);
  auto* quitter = effort("quitter");
  EXPECT_EQ(stateOf("quitter"), ControllerState::stopped);
  EXPECT_EQ(quitter->update_calls, 3);  // two good updates, then deactivate
  EXPECT_EQ(quitter->stopping_calls, 1);
  EXPECT_EQ(quitter->safe_output_calls, 0);
  EXPECT_TRUE(f.manager.processFaults().empty());
  // It can be started again.
  EXPECT_TRUE(f.switchNow({"quitter"}, {}));
}

TEST_F(SwitchTest, BlockingSwitchTimesOutWithoutALoopAndSwitchesNothing) {
  const ServiceResult result = f.manager.switchController({"a"}, {}, SwitchStrictness::STRICT, false, 0.05);
  EXPECT_FALSE(result);
  EXPECT_TRUE(contains(result.message, "did not carry the switch out within")) << result.message;
  EXPECT_FALSE(f.manager.switchPending());
  f.cycles_n(2);
  EXPECT_EQ(stateOf("a"), ControllerState::initialized);
}

TEST_F(SwitchTest, SwitchingFromAnotherThreadWhileTheLoopRuns) {
  eventLogEnabled() = false;
  RealtimeThread loop(f.manager, 0.001);
  ASSERT_TRUE(f.manager.switchController({"b", "state"}, {}, SwitchStrictness::STRICT, false, 5.0));
  for (int i = 0; i < 40; ++i) {
    ASSERT_TRUE(f.manager.switchController({"a"}, {"a_too"}, SwitchStrictness::BEST_EFFORT, false, 5.0)) << i;
    EXPECT_EQ(stateOf("a"), ControllerState::running);
    ASSERT_TRUE(f.manager.switchController({"a_too"}, {"a"}, SwitchStrictness::STRICT, false, 5.0)) << i;
    EXPECT_EQ(stateOf("a_too"), ControllerState::running);
    EXPECT_EQ(stateOf("a"), ControllerState::stopped);
    // Load and unload while the loop iterates the controller list.
    ASSERT_TRUE(f.manager.unloadController("quitter")) << i;
    ASSERT_TRUE(f.manager.loadController("quitter")) << i;
  }
  const long cycles_before = loop.cycles();
  while (loop.cycles() < cycles_before + 20) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  loop.stop();
  // 'b' ran every cycle from its start to the end, through 80 switches and 80
  // reloads of another controller; each blocking switch took at least one cycle.
  auto* b = effort("b");
  EXPECT_GE(b->update_calls, 80 + 20);
  EXPECT_EQ(b->update_calls, std::lround((b->last_update_time - b->starting_time).seconds / 0.001));
  EXPECT_EQ(effort("a")->starting_calls, 40);
  EXPECT_EQ(effort("a_too")->starting_calls, 40);
  EXPECT_TRUE(f.manager.processFaults().empty());
}

TEST_F(SwitchTest, LoadAndUnloadWhileTheLoopRunsBackToBack) {
  // The real-time thread announces the controller list it reads with only a
  // compiler barrier when membarrier(2) is there (src/asymmetric_fence.hpp);
  // a publisher that missed the announcement would free a list entry under
  // it (the sanitizer build reports that; here 'b' would miss updates or the
  // run would crash).
  eventLogEnabled() = false;
  ASSERT_TRUE(f.switchNow({"b"}, {}));
  RealtimeThread loop(f.manager, 0.001, /*spin=*/true);
  for (int i = 0; i < 300; ++i) {
    ASSERT_TRUE(f.manager.unloadController("quitter")) << i;
    ASSERT_TRUE(f.manager.loadController("quitter")) << i;
  }
  const long cycles_before = loop.cycles();
  while (loop.cycles() < cycles_before + 100) std::this_thread::yield();
  loop.stop();
  // 'b' ran in every cycle of the thread, through 600 list changes.
  auto* b = effort("b");
  EXPECT_EQ(b->update_calls, loop.cycles());
  EXPECT_TRUE(f.manager.processFaults().empty());
}

}  // namespace
}  // namespace servoloop::controller_manager::testing
