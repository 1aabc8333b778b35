// Fault containment: a controller that throws, returns ReturnType::error or
// writes a non-finite command is stopped with safe outputs, marked failed and
// reported once; the loop and the other controllers go on.
#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "controller_manager_test_support.hpp"

namespace servoloop::controller_manager::testing {
namespace {

const char* kFaultYaml = R"(
healthy: {type: test_controllers/EffortController, joint: joint2, output: 2.0, record_events: false}
init_throws: {type: test_controllers/EffortController, joint: joint1, fail_in: init}
starting_throws: {type: test_controllers/EffortController, joint: joint1, output: 5.0, fail_in: starting, record_events: false}
update_throws: {type: test_controllers/EffortController, joint: joint1, output: 5.0, fail_in: update, fail_after: 3, record_events: false}
update_error: {type: test_controllers/EffortController, joint: joint1, output: 5.0, fail_in: update_error, fail_after: 3, record_events: false}
writes_nan: {type: test_controllers/EffortController, joint: joint1, output: 5.0, fail_in: nan, fail_after: 3, record_events: false}
position_nan: {type: test_controllers/PositionController, joint: joint3, output: 0.9, fail_in: nan, fail_after: 3, record_events: false}
)";

class FaultTest : public ::testing::Test {
 protected:
  FaultTest() : f(kFaultYaml) {}
  void SetUp() override { ASSERT_TRUE(f.manager.loadController("healthy")); }

  // Loads `name`, starts it with the healthy controller, runs 10 cycles.
  void runWithHealthy(const std::string& name) {
    ASSERT_TRUE(f.manager.loadController(name));
    ASSERT_TRUE(f.switchNow({"healthy", name}, {}));
    f.cycles_n(10);
  }

  // The faulty controller is failed with zero effort, the healthy one kept
  // updating every cycle, and the fault is reported exactly once.
  void expectContained(const std::string& name, FaultKind kind, const std::string& reason_part) {
    auto* faulty = f.get<EffortTestController>(name);
    ASSERT_NE(faulty, nullptr);
    EXPECT_EQ(faulty->state(), ControllerState::failed);
    EXPECT_EQ(faulty->safe_output_calls, 1);
    EXPECT_EQ(faulty->stopping_calls, 0);
    EXPECT_EQ(faulty->update_calls, 4);  // three good updates, then the fault; none after
    EXPECT_DOUBLE_EQ(f.hw.effort_command[0], 0.0);

    auto* healthy = f.get<EffortTestController>("healthy");
    EXPECT_EQ(healthy->state(), ControllerState::running);
    EXPECT_EQ(healthy->update_calls, 10);
    EXPECT_DOUBLE_EQ(f.hw.effort_command[1], 2.0);

    std::vector<ControllerFault> faults;
    std::string log;
    {
      LogCapture capture;
      faults = f.manager.processFaults();
      log = capture.text();
    }
    ASSERT_EQ(faults.size(), 1u);
    EXPECT_EQ(faults[0].controller, name);
    EXPECT_EQ(faults[0].kind, kind);
    EXPECT_TRUE(contains(faults[0].message, "controller '" + name + "'")) << faults[0].message;
    EXPECT_TRUE(contains(faults[0].message, reason_part)) << faults[0].message;
    EXPECT_TRUE(contains(log, "error")) << log;
    EXPECT_TRUE(contains(log, reason_part)) << log;
    EXPECT_TRUE(f.manager.processFaults().empty());  // reported once

    const auto specs = f.manager.listControllers();
    EXPECT_EQ(specs[1].state, ControllerState::failed);
    EXPECT_TRUE(contains(specs[1].last_fault, reason_part)) << specs[1].last_fault;
  }

  ManagerFixture f;
};

TEST_F(FaultTest, InitThrowIsAFailedLoadAndNothingRuns) {
  const ServiceResult result = f.manager.loadController("init_throws");
  EXPECT_FALSE(result);
  EXPECT_TRUE(contains(result.message, "fails in init on purpose")) << result.message;
  ASSERT_TRUE(f.switchNow({"healthy"}, {}));
  f.cycles_n(5);
  EXPECT_EQ(f.get<EffortTestController>("healthy")->update_calls, 5);
  EXPECT_TRUE(f.manager.processFaults().empty());
}

TEST_F(FaultTest, UpdateThrowIsContained) {
  runWithHealthy("update_throws");
  expectContained("update_throws", FaultKind::update_threw,
                  "update() threw: test controller 'update_throws' fails in update on purpose");
}

TEST_F(FaultTest, UpdateReturningErrorIsContained) {
  runWithHealthy("update_error");
  expectContained("update_error", FaultKind::update_returned_error, "returned ReturnType::error");
}

TEST_F(FaultTest, NonFiniteCommandIsContained) {
  runWithHealthy("writes_nan");
  expectContained("writes_nan", FaultKind::non_finite_command,
                  "non-finite command (nan) to 'joint1' through EffortJointInterface");
}

TEST_F(FaultTest, StartingThrowFailsTheSwitchResultButTheOthersStart) {
  ASSERT_TRUE(f.manager.loadController("starting_throws"));
  f.hw.effort_command[0] = 7.0;  // whatever was there before
  RealtimeThread loop(f.manager, 0.001);
  const ServiceResult result =
      f.manager.switchController({"healthy", "starting_throws"}, {}, SwitchStrictness::STRICT, false, 5.0);
  EXPECT_FALSE(result);
  EXPECT_TRUE(contains(result.message, "starting() threw: test controller 'starting_throws' fails in starting on purpose"))
      << result.message;
  const long cycles_after_switch = loop.cycles();
  while (loop.cycles() < cycles_after_switch + 10) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  loop.stop();

  auto* faulty = f.get<EffortTestController>("starting_throws");
  EXPECT_EQ(faulty->state(), ControllerState::failed);
  EXPECT_EQ(faulty->update_calls, 0);
  EXPECT_DOUBLE_EQ(f.hw.effort_command[0], 0.0);
  EXPECT_GE(f.get<EffortTestController>("healthy")->update_calls, 9);
  // The switch already reported (and logged) it.
  EXPECT_TRUE(f.manager.processFaults().empty());
  EXPECT_TRUE(contains(f.manager.listControllers()[1].last_fault, "starting() threw"));
}

TEST_F(FaultTest, StartingThrowOnTheManualLoopIsReportedByProcessFaults) {
  ASSERT_TRUE(f.manager.loadController("starting_throws"));
  ASSERT_TRUE(f.switchNow({"starting_throws"}, {}));
  f.cycles_n(3);
  const auto faults = f.manager.processFaults();
  ASSERT_EQ(faults.size(), 1u);
  EXPECT_EQ(faults[0].kind, FaultKind::starting_threw);
  EXPECT_EQ(f.get<EffortTestController>("starting_throws")->update_calls, 0);
}

TEST_F(FaultTest, PositionControllerFaultHoldsTheMeasuredPosition) {
  ASSERT_TRUE(f.manager.loadController("position_nan"));
  ASSERT_TRUE(f.switchNow({"position_nan"}, {}));
  f.cycles_n(3);
  EXPECT_DOUBLE_EQ(f.hw.position_command[2], 0.9);
  f.cycle();  // the NaN update
  EXPECT_EQ(f.manager.getController("position_nan")->state(), ControllerState::failed);
  EXPECT_DOUBLE_EQ(f.hw.position_command[2], f.hw.position[2]);
  EXPECT_EQ(f.manager.processFaults().size(), 1u);
}

TEST_F(FaultTest, FailedControllerCanBeRestartedAndUnloaded) {
  runWithHealthy("update_error");
  f.manager.processFaults();
  // Restart: it runs again; its update count is past fail_after, so its very
  // next update fails again, and that fault is reported too.
  ASSERT_TRUE(f.switchNow({"update_error"}, {}));
  auto* restarted = f.get<EffortTestController>("update_error");
  EXPECT_EQ(restarted->state(), ControllerState::running);
  EXPECT_EQ(restarted->starting_calls, 2);
  f.cycle();
  EXPECT_EQ(restarted->state(), ControllerState::failed);
  EXPECT_EQ(f.manager.processFaults().size(), 1u);
  EXPECT_TRUE(f.manager.unloadController("update_error"));
}

TEST_F(FaultTest, StoppingAFailedControllerIsRefusedByStrict) {
  runWithHealthy("update_throws");
  const ServiceResult result = f.switchNow({}, {"update_throws"});
  EXPECT_FALSE(result);
  EXPECT_TRUE(contains(result.message, "it is not running (it is failed)")) << result.message;
}

}  // namespace
}  // namespace servoloop::controller_manager::testing
