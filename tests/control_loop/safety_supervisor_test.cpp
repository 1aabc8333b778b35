// The safety states on the control loops: each transition of
// safety_supervisor.hpp with the fake hardware (read, write and step
// failures, deactivate, the hardware's emergency-stop input), on the
// simulation loop and on the wall clock, checked against what the hardware
// was sent.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <thread>

#include "control_loop_test_support.hpp"
#include "servoloop/controller_manager/safety_supervisor.hpp"
#include "servoloop/controller_manager/simulation_loop.hpp"
#include "servoloop/controller_manager/wall_clock_loop.hpp"

namespace servoloop::controller_manager {
namespace {

using testing::EventKind;
using testing::LoopFixture;

// The fake robot with an emergency-stop input the test presses.
class FakeRobotWithEstopInput : public testing::FakeSimulatedRobotHW {
 public:
  using FakeSimulatedRobotHW::FakeSimulatedRobotHW;
  bool emergencyStopInput() const noexcept override { return pressed.load(); }
  std::atomic<bool> pressed{false};
};

// The effort each write() sent, in order.
std::vector<double> writtenEfforts(const testing::EventRecorder& recorder) {
  std::vector<double> efforts;
  for (const testing::Event& e : recorder.ofKind(EventKind::write)) efforts.push_back(e.command);
  return efforts;
}

struct SafetyLoop {
  explicit SafetyLoop(LoopFixture& f) : safety(f.hw) {
    SimulationLoop::Options options;
    options.safety = &safety;
    loop = std::make_unique<SimulationLoop>(f.hw, f.manager, options);
    f.requestStart();
    loop->cycleOnce();  // carries out the switch
  }
  SafetySupervisor safety;
  std::unique_ptr<SimulationLoop> loop;
};

// The same under the supervisor with no controller running yet, after one cycle.
struct IdleSafetyLoop {
  explicit IdleSafetyLoop(LoopFixture& f) : safety(f.hw), loop(f.hw, f.manager, options()) {
    loop.cycleOnce();
  }
  SimulationLoop::Options options() {
    SimulationLoop::Options o;
    o.safety = &safety;
    return o;
  }
  SafetySupervisor safety;
  SimulationLoop loop;
};

TEST(SafetySupervisor, EmergencyStopZeroesEffortWhileTheControllerRunsOnAndReleaseRestoresIt) {
  LoopFixture f(0.001);
  SafetyLoop s(f);
  ASSERT_TRUE(f.controller()->isRunning());
  EXPECT_EQ(s.safety.state(), SafetyState::running);
  for (int i = 0; i < 5; ++i) s.loop->cycleOnce();

  s.safety.engageEmergencyStop(EmergencyStopSource::command);
  EXPECT_EQ(s.safety.state(), SafetyState::emergency_stop);
  f.recorder->clear();
  const std::uint64_t updates_before = f.controller()->updates;
  for (int i = 0; i < 10; ++i) s.loop->cycleOnce();
  // The controller keeps running (its state goes on), the hardware gets 0.
  EXPECT_EQ(f.controller()->updates, updates_before + 10);
  EXPECT_TRUE(f.controller()->isRunning());
  for (double effort : writtenEfforts(*f.recorder)) EXPECT_EQ(effort, 0.0);
  EXPECT_EQ(writtenEfforts(*f.recorder).size(), 10u);

  std::string why;
  ASSERT_TRUE(s.safety.releaseEmergencyStop(&why)) << why;
  EXPECT_EQ(s.safety.state(), SafetyState::running);
  f.recorder->clear();
  s.loop->cycleOnce();
  EXPECT_EQ(writtenEfforts(*f.recorder), std::vector<double>{2.5});  // the controller's own output again
  EXPECT_EQ(s.safety.emergencyStops(), 1u);
}

TEST(SafetySupervisor, ReadErrorIsAProtectiveStopThatStopsTheControllerAndStaysLatched) {
  LoopFixture f(0.001);
  SafetyLoop s(f);
  const std::uint64_t first_failing_read = f.hw.reads + 3;
  f.hw.read_script.from = first_failing_read;
  f.hw.read_script.until = first_failing_read + 1;  // one failed read, then the hardware is fine again
  f.recorder->clear();
  for (int i = 0; i < 10; ++i) s.loop->cycleOnce();

  EXPECT_EQ(s.safety.state(), SafetyState::protective_stop);
  EXPECT_EQ(s.safety.protectiveStops(), 1u);
  EXPECT_EQ(f.controller()->state(), ControllerState::failed);
  // Written: 2.5 for the three good cycles, then the safe effort 0 from the
  // failing cycle on, though the hardware works again (the stop is latched).
  const std::vector<double> efforts = writtenEfforts(*f.recorder);
  ASSERT_EQ(efforts.size(), 10u);
  for (std::size_t i = 0; i < efforts.size(); ++i) EXPECT_EQ(efforts[i], i < 3 ? 2.5 : 0.0) << "write " << i;
  EXPECT_NE(s.safety.reason().find("read() returned an error"), std::string::npos) << s.safety.reason();

  const std::vector<ControllerFault> faults = f.manager.processFaults();
  ASSERT_EQ(faults.size(), 1u);
  EXPECT_EQ(faults[0].kind, FaultKind::hardware_failed);
  EXPECT_NE(faults[0].message.find("the hardware failed: its read() returned an error (protective stop)"), std::string::npos)
      << faults[0].message;
  const std::vector<ControllerSpec> specs = f.manager.listControllers();
  EXPECT_EQ(specs[0].last_fault_kind, FaultKind::hardware_failed);

  // Recovery: the state clears, and the controller can be started again.
  s.safety.clearStop();
  EXPECT_EQ(s.safety.state(), SafetyState::running);
  f.requestStart();
  s.loop->cycleOnce();
  EXPECT_TRUE(f.controller()->isRunning());
  f.recorder->clear();
  s.loop->cycleOnce();
  EXPECT_EQ(writtenEfforts(*f.recorder), std::vector<double>{2.5});
}

// A read() that returns ok but leaves a joint's position NaN (a driver that
// lost its encoder, an engine whose state blew up) is a failed read: counted,
// reported once naming the joint and the value, a protective stop that stops
// the controller with its safe output; the loop runs on.
TEST(SafetySupervisor, ANaNJointStateFromReadIsAReadErrorNamingTheJointAndContainsTheController) {
  LoopFixture f(0.001);
  SafetyLoop s(f);  // cycle 0 (read 0) done
  f.hw.nan_position_from = 20;  // read 20 is cycle 20's
  f.hw.nan_position_until = 21;
  f.recorder->clear();
  for (int i = 0; i < 40; ++i) s.loop->cycleOnce();  // cycles 1..40

  const LoopStatisticsSnapshot stats = s.loop->statistics().snapshot();
  EXPECT_EQ(stats.hardware_errors, 1u);
  const auto report = s.loop->takeHardwareErrorReport();
  ASSERT_TRUE(report.has_value());
  EXPECT_EQ(report->call, HardwareCall::read);
  EXPECT_EQ(report->cycle, 20u);
  EXPECT_NE(report->message().find("read() gave joint 'joint1' a position of nan"), std::string::npos)
      << report->message();
  EXPECT_NE(report->message().find("(cycle 20)"), std::string::npos) << report->message();
  EXPECT_FALSE(s.loop->takeHardwareErrorReport().has_value());  // once

  // Contained: protective stop, the controller failed, the safe effort 0
  // written from the failing cycle on.
  EXPECT_EQ(s.safety.state(), SafetyState::protective_stop);
  EXPECT_EQ(s.safety.protectiveStops(), 1u);
  EXPECT_EQ(f.controller()->state(), ControllerState::failed);
  const std::vector<double> efforts = writtenEfforts(*f.recorder);
  ASSERT_EQ(efforts.size(), 40u);
  for (std::size_t i = 0; i < efforts.size(); ++i) EXPECT_EQ(efforts[i], i < 19 ? 2.5 : 0.0) << "write " << i;
  const std::vector<ControllerFault> faults = f.manager.processFaults();
  ASSERT_EQ(faults.size(), 1u);
  EXPECT_EQ(faults[0].kind, FaultKind::hardware_failed);
  EXPECT_NE(faults[0].message.find("its read() gave a joint state that is not a finite number"), std::string::npos)
      << faults[0].message;

  // The loop ran on, and the hardware's later (finite) reads are no errors.
  EXPECT_EQ(s.loop->stepsTaken(), 41u);
  EXPECT_FALSE(s.loop->hardwareAskedToStop());
  EXPECT_TRUE(std::isfinite(f.hw.position));
}

// Without a safety layer a non-finite joint state is counted and reported
// like any read error, as long as it lasts; an infinite value is named too.
TEST(SafetySupervisor, WithoutTheSupervisorANaNReadIsCountedAndReportedLikeAReadError) {
  LoopFixture f(0.001);
  SimulationLoop loop(f.hw, f.manager);
  f.hw.nan_position_from = 5;  // reads 5, 6, 7
  f.hw.nan_position_until = 8;
  loop.runFor(Duration(0.02));
  EXPECT_EQ(loop.stepsTaken(), 20u);
  EXPECT_EQ(loop.statistics().snapshot().hardware_errors, 3u);
  const auto report = loop.takeHardwareErrorReport();
  ASSERT_TRUE(report.has_value());
  EXPECT_EQ(report->cycle, 5u);
  EXPECT_NE(report->message().find("joint 'joint1' a position of nan"), std::string::npos) << report->message();
  EXPECT_FALSE(loop.takeHardwareErrorReport().has_value());  // one episode, one report

  f.hw.velocity = std::numeric_limits<double>::infinity();
  EXPECT_EQ(loop.cycleOnce(), ReturnType::error);
  const auto second = loop.takeHardwareErrorReport();
  ASSERT_TRUE(second.has_value());
  EXPECT_NE(second->message().find("joint 'joint1' a velocity of inf"), std::string::npos) << second->message();
}

TEST(SafetySupervisor, WriteAndStepErrorsAreProtectiveStopsToo) {
  for (const char* which : {"write", "step"}) {
    SCOPED_TRACE(which);
    LoopFixture f(0.001);
    SafetyLoop s(f);
    testing::FakeSimulatedRobotHW::Script& script =
        std::string(which) == "write" ? f.hw.write_script : f.hw.step_script;
    const std::uint64_t from = (std::string(which) == "write" ? f.hw.writes : f.hw.steps) + 2;
    script.from = from;
    script.until = from + 1;
    for (int i = 0; i < 5; ++i) s.loop->cycleOnce();
    EXPECT_EQ(s.safety.state(), SafetyState::protective_stop);
    EXPECT_EQ(f.controller()->state(), ControllerState::failed);
    EXPECT_NE(s.safety.reason().find(std::string(which) + "() returned an error"), std::string::npos)
        << s.safety.reason();
  }
}

TEST(SafetySupervisor, AProtectiveStopStartsTheFallbackController) {
  testing::EventRecorder recorder;
  testing::FakeSimulatedRobotHW hw(0.001, &recorder);
  auto factory = std::make_shared<InProcessControllerFactory>();
  factory->add("test/RecordingController", [&recorder] {
    return ControllerPtr(new testing::RecordingController(&recorder), [](ControllerBase* c) { delete c; });
  });
  const YAML::Node params = YAML::Load(
      "hold: {type: test/RecordingController, joint: joint1, output: 0.5}\n"
      "ctrl: {type: test/RecordingController, joint: joint1, output: 2.5, fallback_controllers: [hold]}");
  ControllerManager manager(&hw, factory, ControllerManager::lookupIn(params), LoopFixture::context(), 0.0);
  ASSERT_TRUE(manager.loadController("hold"));
  ASSERT_TRUE(manager.loadController("ctrl"));
  SafetySupervisor safety(hw);
  SimulationLoop::Options options;
  options.safety = &safety;
  SimulationLoop loop(hw, manager, options);
  ASSERT_TRUE(manager.requestSwitch(SwitchRequest{{"ctrl"}, {}, SwitchStrictness::STRICT, false, 0.0}));
  loop.cycleOnce();
  hw.read_script.from = hw.reads;
  hw.read_script.until = hw.reads + 1;
  recorder.clear();
  loop.cycleOnce();  // read fails: ctrl stops, hold starts; its first update is the next cycle
  loop.cycleOnce();
  EXPECT_EQ(safety.state(), SafetyState::protective_stop);
  EXPECT_EQ(manager.getController("ctrl")->state(), ControllerState::failed);
  EXPECT_TRUE(manager.getController("hold")->isRunning());
  const std::vector<double> efforts = writtenEfforts(recorder);
  // The fallback drives the joint from the failing cycle on (at this
  // manager's rate it updates in the cycle it started).
  EXPECT_EQ(efforts, (std::vector<double>{0.5, 0.5}));
  const std::vector<ControllerFault> faults = manager.processFaults();
  ASSERT_EQ(faults.size(), 1u);
  EXPECT_NE(faults[0].message.find("fallback controller(s) 'hold' started"), std::string::npos) << faults[0].message;
}

TEST(SafetySupervisor, DeactivateIsAFaultThatStopsTheLoop) {
  LoopFixture f(0.001);
  SafetyLoop s(f);
  f.hw.write_script.from = f.hw.writes + 2;
  f.hw.write_script.result = ReturnType::deactivate;
  s.loop->runFor(Duration(0.05));
  EXPECT_TRUE(s.loop->hardwareAskedToStop());
  EXPECT_EQ(s.safety.state(), SafetyState::fault);
  EXPECT_EQ(f.controller()->state(), ControllerState::failed);
  EXPECT_NE(s.safety.reason().find("write() returned deactivate"), std::string::npos) << s.safety.reason();
  s.safety.clearStop();
  s.loop->clearHardwareStop();
  EXPECT_EQ(s.safety.state(), SafetyState::running);
}

TEST(SafetySupervisor, ADeactivatingReadIsContainedBeforeThatCyclesUpdateAndWrite) {
  LoopFixture f(0.001);
  SafetyLoop s(f);
  f.hw.read_script.from = f.hw.reads + 2;
  f.hw.read_script.result = ReturnType::deactivate;
  f.recorder->clear();
  s.loop->runFor(Duration(0.05));
  EXPECT_TRUE(s.loop->hardwareAskedToStop());
  EXPECT_EQ(s.safety.state(), SafetyState::fault);
  EXPECT_EQ(f.controller()->state(), ControllerState::failed);
  EXPECT_NE(s.safety.reason().find("read() returned deactivate"), std::string::npos) << s.safety.reason();
  // Two good cycles (2.5), then the deactivating one: its write already
  // carries the stopped controller's safe effort, and the loop ends there.
  EXPECT_EQ(writtenEfforts(*f.recorder), (std::vector<double>{2.5, 2.5, 0.0}));
  EXPECT_EQ(f.recorder->ofKind(EventKind::update).size(), 2u);
  const std::vector<ControllerFault> faults = f.manager.processFaults();
  ASSERT_EQ(faults.size(), 1u);
}

TEST(SafetySupervisor, ASwitchWaitingWhenTheHardwareFailsStartsNothing) {
  // Nothing commands the robot yet; a start of ctrl waits for the next
  // update. The read before it fails (an error, then, separately, a
  // deactivate): the waiting start is dropped, the hardware gets no command.
  for (const ReturnType failure : {ReturnType::error, ReturnType::deactivate}) {
    SCOPED_TRACE(failure == ReturnType::error ? "error" : "deactivate");
    LoopFixture f(0.001);
    IdleSafetyLoop rig(f);
    SafetySupervisor& safety = rig.safety;
    SimulationLoop& loop = rig.loop;
    f.hw.read_script.from = f.hw.reads;
    f.hw.read_script.until = f.hw.reads + 1;
    f.hw.read_script.result = failure;
    f.requestStart();
    f.recorder->clear();
    loop.cycleOnce();
    EXPECT_FALSE(f.controller()->isRunning());
    EXPECT_TRUE(f.recorder->ofKind(EventKind::update).empty());
    EXPECT_EQ(writtenEfforts(*f.recorder), std::vector<double>{0.0});
    EXPECT_EQ(safety.state(), failure == ReturnType::error ? SafetyState::protective_stop : SafetyState::fault);
  }
}

TEST(SafetySupervisor, AProtectiveStopBeginningWhileASwitchIsCheckedStartsNothing) {
  // A start request is checked against the safety state (the node's guard
  // refuses starts under a protective stop). The real-time thread's read
  // fails right after the guard looked: the guard saw a running robot and
  // allowed the start, yet the stop that began since must drop it.
  LoopFixture f(0.001);
  IdleSafetyLoop rig(f);
  SafetySupervisor& safety = rig.safety;
  SimulationLoop& loop = rig.loop;
  int checks = 0;
  f.manager.setSwitchGuard([&](const SwitchRequest&) -> std::string {
    ++checks;
    const bool stopped = safety.protectiveStopped();
    f.hw.read_script.from = f.hw.reads;  // the next read fails: a protective stop
    f.hw.read_script.until = f.hw.reads + 1;
    loop.cycleOnce();
    return stopped ? "protective stop" : "";
  });
  f.requestStart();
  ASSERT_EQ(checks, 1);
  EXPECT_EQ(safety.state(), SafetyState::protective_stop);
  f.recorder->clear();
  loop.cycleOnce();
  EXPECT_FALSE(f.controller()->isRunning());
  EXPECT_TRUE(f.recorder->ofKind(EventKind::update).empty());
  EXPECT_EQ(writtenEfforts(*f.recorder), std::vector<double>{0.0});
  EXPECT_FALSE(f.manager.finishSwitch());  // says why it was dropped
}

TEST(SafetySupervisor, PersistentErrorsEndInAFaultKeepingTheFirstCause) {
  LoopFixture f(0.001);
  SafetySupervisor safety(f.hw);
  SimulationLoop::Options options;
  options.safety = &safety;
  options.stop_after_failed_cycles = 5;
  SimulationLoop loop(f.hw, f.manager, options);
  f.requestStart();
  loop.cycleOnce();
  f.hw.read_script.from = f.hw.reads;
  loop.runFor(Duration(0.1));
  EXPECT_TRUE(loop.hardwareAskedToStop());
  EXPECT_EQ(loop.stepsTaken(), 6u);  // the start-up cycle and five failing ones
  EXPECT_EQ(safety.state(), SafetyState::fault);
  EXPECT_NE(safety.reason().find("read() returned an error"), std::string::npos) << safety.reason();
}

// A robot with an emergency-stop input under the supervisor, its controller
// started and updated once (so it commands 2.5).
template <class Robot>
struct EstopInputLoop {
  EstopInputLoop(LoopFixture& f, testing::EventRecorder* recorder)
      : hw(0.001, recorder),
        safety(hw),
        manager(&hw, f.factory, ControllerManager::lookupIn(f.params), LoopFixture::context(), 0.0) {
    EXPECT_TRUE(manager.loadController("ctrl"));
    SimulationLoop::Options options;
    options.safety = &safety;
    loop = std::make_unique<SimulationLoop>(hw, manager, options);
    EXPECT_TRUE(manager.requestSwitch(SwitchRequest{{"ctrl"}, {}, SwitchStrictness::STRICT, false, 0.0}));
    loop->cycleOnce();  // starts ctrl
    loop->cycleOnce();  // its first update
  }
  Robot hw;
  SafetySupervisor safety;
  ControllerManager manager;
  std::unique_ptr<SimulationLoop> loop;
};

TEST(SafetySupervisor, TheReasonNamesWhoLatchedTheStopNotWhoPressedItLater) {
  LoopFixture f(0.001);
  SafetySupervisor safety(f.hw);
  EXPECT_EQ(safety.reason(), "");
  safety.engageEmergencyStop(EmergencyStopSource::topic);
  safety.engageEmergencyStop(EmergencyStopSource::command);  // already latched: no second stop
  EXPECT_EQ(safety.emergencyStops(), 1u);
  EXPECT_NE(safety.reason().find("engaged by topic:"), std::string::npos) << safety.reason();
  ASSERT_TRUE(safety.releaseEmergencyStop(nullptr));
  EXPECT_EQ(safety.state(), SafetyState::running);
  safety.engageEmergencyStop(EmergencyStopSource::command);
  EXPECT_EQ(safety.emergencyStops(), 2u);
  EXPECT_NE(safety.reason().find("engaged by command:"), std::string::npos) << safety.reason();
}

TEST(SafetySupervisor, TheHardwareInputLatchesTheStopAndBlocksItsRelease) {
  LoopFixture f(0.001);
  EstopInputLoop<FakeRobotWithEstopInput> rig(f, f.recorder);
  auto& hw = rig.hw;
  auto& safety = rig.safety;
  SimulationLoop& loop = *rig.loop;
  EXPECT_EQ(hw.applied_effort, 2.5);

  hw.pressed = true;
  loop.cycleOnce();
  EXPECT_EQ(safety.state(), SafetyState::emergency_stop);
  EXPECT_EQ(hw.applied_effort, 0.0);
  std::string why;
  EXPECT_FALSE(safety.releaseEmergencyStop(&why));
  EXPECT_NE(why.find("input is still active"), std::string::npos) << why;
  // What the node logs and `control stats` shows: who, what it does, how to release it.
  EXPECT_NE(safety.emergencyStopText().find("engaged by hardware input: effort and velocity commands are 0, "
                                            "position commands hold; the hardware's input is still active: "
                                            "release it on the robot"),
            std::string::npos)
      << safety.emergencyStopText();
  EXPECT_EQ(safety.reason(), safety.emergencyStopText());

  hw.pressed = false;
  loop.cycleOnce();
  EXPECT_EQ(safety.state(), SafetyState::emergency_stop);  // latched until released
  EXPECT_NE(safety.reason().find("engaged by hardware input: effort and velocity commands are 0, position commands "
                                 "hold; release with `servoloop control estop off`"),
            std::string::npos)
      << safety.reason();
  EXPECT_EQ(hw.applied_effort, 0.0);
  ASSERT_TRUE(safety.releaseEmergencyStop(&why));
  loop.cycleOnce();
  EXPECT_EQ(hw.applied_effort, 2.5);
}

// The input as the last poll saw it, and every write that carried the
// controller's effort while it was pressed.
class InputCheckingRobot : public FakeRobotWithEstopInput {
 public:
  using FakeRobotWithEstopInput::FakeRobotWithEstopInput;
  bool emergencyStopInput() const noexcept override {
    last_seen_ = pressed.load();
    return last_seen_;
  }
  ReturnType write(Time time, Duration period) override {
    if (last_seen_ && effort_command != 0.0) ++unsafe_writes;
    return FakeRobotWithEstopInput::write(time, period);
  }
  int unsafe_writes = 0;  // loop thread only

 private:
  mutable bool last_seen_ = false;
};

TEST(SafetySupervisor, AReleaseRacingTheHardwareInputNeverLetsACommandOutWhileItIsPressed) {
  // The input toggles every 3 cycles (on the loop thread, between cycles)
  // while another thread asks for a release as fast as it can. A release
  // that checked the input just before a poll saw it pressed must not clear
  // the stop that poll relies on: no write may carry the controller's 2.5
  // while the input is pressed.
  LoopFixture f(0.001);
  EstopInputLoop<InputCheckingRobot> rig(f, nullptr);
  auto& hw = rig.hw;
  auto& safety = rig.safety;
  SimulationLoop& loop = *rig.loop;
  ASSERT_EQ(hw.applied_effort, 2.5);

  std::atomic<bool> done{false};
  std::atomic<long> releases{0};
  std::thread releaser([&] {
    while (!done.load(std::memory_order_relaxed)) {
      if (safety.releaseEmergencyStop(nullptr)) releases.fetch_add(1, std::memory_order_relaxed);
    }
  });
  int commanded_writes = 0;
  for (int cycle = 0; cycle < 200000; ++cycle) {
    hw.pressed.store(cycle % 6 < 3);
    loop.cycleOnce();
    if (hw.applied_effort == 2.5) ++commanded_writes;
  }
  done.store(true);
  releaser.join();
  EXPECT_EQ(hw.unsafe_writes, 0);
  // The test did exercise both: releases that went through, and the
  // controller's effort reaching the hardware between presses.
  EXPECT_GT(releases.load(), 0);
  EXPECT_GT(commanded_writes, 0);
}

// A robot with one position-commanded joint: the held value.
class PositionRobot : public hardware_interface::RobotHW {
 public:
  PositionRobot() {
    hardware_interface::JointStateHandle state("joint1", &position, &velocity, &effort);
    state_interface.registerHandle(state);
    position_interface.registerHandle(hardware_interface::JointHandle(state, &position_command));
    velocity_interface.registerHandle(hardware_interface::JointHandle(state, &velocity_command));
    registerInterface(&state_interface);
    registerInterface(&position_interface);
    registerInterface(&velocity_interface);
  }
  void init(const hardware_interface::HardwareInfo&) override {}
  ReturnType read(Time, Duration) override { return ReturnType::ok; }
  ReturnType write(Time, Duration) override { return ReturnType::ok; }
  double position = 0.0, velocity = 0.0, effort = 0.0;
  double position_command = 0.0, velocity_command = 0.0;
  hardware_interface::JointStateInterface state_interface;
  hardware_interface::PositionJointInterface position_interface;
  hardware_interface::VelocityJointInterface velocity_interface;
};

TEST(SafetySupervisor, EmergencyStopHoldsPositionJointsWhereTheyWereWhenItEngaged) {
  PositionRobot hw;
  SafetySupervisor safety(hw);
  // Building the supervisor claims nothing.
  EXPECT_TRUE(hw.position_interface.getClaims().empty());
  hw.position = 0.68;  // measured
  hw.position_command = 0.7;
  hw.velocity_command = 0.3;
  safety.overrideCommands();  // running: untouched
  EXPECT_EQ(hw.position_command, 0.7);
  EXPECT_EQ(hw.velocity_command, 0.3);

  safety.engageEmergencyStop(EmergencyStopSource::topic);
  safety.overrideCommands();
  EXPECT_EQ(hw.position_command, 0.68);  // where the joint is, not where it was going
  EXPECT_EQ(hw.velocity_command, 0.0);
  hw.position_command = 1.9;  // a controller goes on commanding
  hw.velocity_command = 0.3;
  hw.position = 0.69;         // and the joint settles a little
  safety.overrideCommands();
  EXPECT_EQ(hw.position_command, 0.68);  // the hold does not follow it
  EXPECT_EQ(hw.velocity_command, 0.0);
  EXPECT_NE(safety.reason().find("engaged by topic"), std::string::npos) << safety.reason();

  ASSERT_TRUE(safety.releaseEmergencyStop(nullptr));
  hw.position_command = 1.9;
  safety.overrideCommands();
  EXPECT_EQ(hw.position_command, 1.9);
  // A second stop holds the position of its own moment.
  hw.position = 1.85;
  safety.engageEmergencyStop(EmergencyStopSource::command);
  safety.overrideCommands();
  hw.position_command = -1.0;
  safety.overrideCommands();
  EXPECT_EQ(hw.position_command, 1.85);
  // Without a finite measured position, the command at the stop is held.
  ASSERT_TRUE(safety.releaseEmergencyStop(nullptr));
  safety.overrideCommands();
  hw.position = std::numeric_limits<double>::quiet_NaN();
  hw.position_command = 0.4;
  safety.engageEmergencyStop(EmergencyStopSource::command);
  safety.overrideCommands();
  hw.position_command = 3.0;
  safety.overrideCommands();
  EXPECT_EQ(hw.position_command, 0.4);
}

TEST(SafetySupervisor, OnTheWallClockAReadErrorStopsTheControllerAndTheLoopKeepsItsRate) {
  LoopFixture f(0.002, 500.0);
  f.recorder->enabled = false;
  SafetySupervisor safety(f.hw);
  WallClockLoop::Options options;
  options.safety = &safety;
  options.step_simulation = true;
  WallClockLoop loop(f.hw, f.manager, options);
  f.requestStart();
  f.hw.read_script.from = 20;
  f.hw.read_script.until = 30;
  loop.runFor(Duration(0.2));  // 100 cycles
  const LoopStatisticsSnapshot stats = loop.statistics().snapshot();
  EXPECT_EQ(safety.state(), SafetyState::protective_stop);
  EXPECT_EQ(f.controller()->state(), ControllerState::failed);
  EXPECT_EQ(f.hw.applied_effort, 0.0);
  EXPECT_EQ(stats.hardware_errors, 10u);
  // It kept cycling after the stop, on its grid: every one of the 100
  // deadlines ran a cycle or was skipped (a loaded machine makes it skip some;
  // an overrun of the last cycle also skips deadlines past the run's end).
  EXPECT_GE(stats.cycles + stats.skipped_deadlines, 100u);
  if (stats.overruns == 0) EXPECT_EQ(stats.cycles + stats.skipped_deadlines, 100u);
  EXPECT_GT(stats.cycles, 30u);
  EXPECT_FALSE(loop.hardwareAskedToStop());
}

}  // namespace
}  // namespace servoloop::controller_manager
