// The safety states through the command line, on a running node:
//   - hardware on the wall clock (servoloop_test/ScriptedHardware, whose
//     failures the test switches through its control file): emergency stop
//     by command, topic and the hardware's input; protective stops from read
//     and write errors and their recovery; a refused mode switch; a stall;
//     a fault from a hardware that deactivates, and its recovery. After each,
//     the node still answers and the joint still follows its commands.
//   - a simulated robot (the seed on bullet): an emergency stop removes the
//     effort holding the arm against gravity, and the release brings it back.
#include <csignal>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iterator>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_client_support.hpp"

namespace servoloop::cli::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using json = nlohmann::json;

const fs::path kOneDof = fs::path(SERVOLOOP_SOURCE_DIR) / "robots" / "one_dof";
const char* const kJointStates = "/one_DOF_robot/joint_states";
constexpr double kWait_s = 30.0;

class SafetyCli : public ::testing::Test {
 protected:
  const fs::path& scratch() const { return run_dir_.scratch(); }

  CliResult cli(const std::vector<std::string>& args) { return runCli(args, scratch(), kWait_s); }

  // Polls until `done` holds, up to kWait_s.
  bool waitFor(const std::function<bool()>& done) { return waitUntil(done, kWait_s); }

  bool waitForNode() {
    return waitFor([this] { return cli({"control", "safety"}).status == 0; });
  }

  json safety() {
    const CliResult result = cli({"control", "safety", "--json"});
    EXPECT_EQ(result.status, 0) << result.err;
    return result.status == 0 ? json::parse(result.out) : json::object();
  }
  std::string state() { return safety().value("state", ""); }

  // The next n joint states (one JSON message each).
  std::vector<json> jointStates(int n) {
    const CliResult echo = cli({"topic", "echo", "-n", std::to_string(n), "--json", kJointStates});
    EXPECT_EQ(echo.status, 0) << echo.err;
    std::vector<json> messages;
    std::istringstream lines(echo.out);
    std::string line;
    while (std::getline(lines, line)) {
      if (!line.empty()) messages.push_back(json::parse(line));
    }
    return messages;
  }
  static double position(const json& message) { return message.at("position").at(0).get<double>(); }
  static double effort(const json& message) { return message.at("effort").at(0).get<double>(); }

  bool positionReaches(double target, double tolerance) {
    return waitFor([&] {
      const std::vector<json> states = jointStates(1);
      return !states.empty() && std::abs(position(states[0]) - target) < tolerance;
    });
  }

  std::string controllerState(const std::string& name) {
    const CliResult list = cli({"control", "list", "--json"});
    EXPECT_EQ(list.status, 0) << list.err;
    for (const json& controller : json::parse(list.out)) {
      if (controller.value("name", "") == name) return controller.value("state", "");
    }
    return "";
  }

  ScopedRunDir run_dir_;
};

class SafetyOnHardware : public SafetyCli {
 protected:
  // The robot's description (the seed's unless a test says otherwise).
  virtual fs::path urdf() { return kOneDof / "minimal_robot_description_w_jnt_ctl.urdf"; }

  void SetUp() override {
    control_file_ = scratch() / "hardware_control";
    script("");
    std::ofstream(scratch() / "controllers.yaml")
        << "one_DOF_robot:\n"
           "  joint_state_controller: {type: joint_state_controller/JointStateController, publish_rate: 100}\n"
           "  position_controller: {type: position_controllers/JointPositionController, joint: joint1}\n";
    std::ofstream(scratch() / "hw.launch.yaml")
        << "controller_manager: {update_rate: 500}\n"
           "robots:\n"
           "  - urdf: '" << urdf().string() << "'\n"
           "    model: one_DOF_robot\n"
           "    params: ['" << (scratch() / "controllers.yaml").string() << "']\n"
           "    hardware: {type: servoloop_test/ScriptedHardware, joints: [joint1], control_file: '"
        << control_file_.string() << "'}\n"
           "    controllers: [joint_state_controller, position_controller]\n";
    node_.emplace(std::vector<std::string>{"launch", (scratch() / "hw.launch.yaml").string(), "--plugin-dir",
                                           SERVOLOOP_SAFETY_PLUGIN_DIR},
                  scratch());
    ASSERT_TRUE(waitForNode()) << node_->currentOut();
  }

  void TearDown() override {
    if (!node_) return;
    node_->signal(SIGINT);
    const CliResult ended = node_->wait(kWait_s);
    EXPECT_FALSE(ended.timed_out);
  }

  // Replaces the hardware's control file (written aside and renamed, so the
  // plugin never reads half of it).
  void script(const std::string& lines) {
    const fs::path aside = control_file_.string() + ".new";
    std::ofstream(aside) << lines;
    fs::rename(aside, control_file_);
  }

  void command(double position) {
    const CliResult pub = cli({"topic", "pub", "/one_DOF_robot/position_controller/command", "std_msgs/Float64",
                               std::to_string(position)});
    ASSERT_EQ(pub.status, 0) << pub.err;
  }

  // The loop goes on at its 500 Hz: over the next 100 cycles, the loop's own
  // time advanced by 2 ms per deadline of its grid (the cycles run and the
  // deadlines an overrun skipped), up to the wake-up latency at the two ends.
  // A loop that stopped never gets there; one on another rate is off by far.
  void expectLoopKeepsItsRate() {
    const auto loopStats = [&] {
      const CliResult stats = cli({"control", "stats", "--json"});
      EXPECT_EQ(stats.status, 0) << stats.err;
      return stats.status == 0 ? json::parse(stats.out).at("loop") : json::object();
    };
    const json before = loopStats();
    ASSERT_TRUE(before.contains("cycles"));
    json after;
    ASSERT_TRUE(waitFor([&] {
      after = loopStats();
      return after.value("cycles", 0.0) >= before.at("cycles").get<double>() + 100.0;
    })) << "the loop stopped cycling";
    const auto deadlines = [](const json& loop) {
      return loop.at("cycles").get<double>() + loop.at("skipped_deadlines").get<double>();
    };
    const double grid = deadlines(after) - deadlines(before);
    const double seconds = after.at("sim_time").get<double>() - before.at("sim_time").get<double>();
    EXPECT_NEAR(seconds * 500.0, grid, 3.0 + 0.1 * grid)
        << seconds << " s for " << grid << " deadlines (" << after.dump() << ")";
  }

  fs::path control_file_;
  std::optional<CliProcess> node_;
};

TEST_F(SafetyOnHardware, EmergencyStopByCommandTopicAndHardwareInputHoldsThePosition) {
  EXPECT_EQ(state(), "running");
  command(0.5);
  ASSERT_TRUE(positionReaches(0.5, 1e-9));

  // By command: the joint holds while the controller is commanded elsewhere.
  CliResult estop = cli({"control", "estop", "on"});
  ASSERT_EQ(estop.status, 0) << estop.err;
  EXPECT_THAT(estop.out, HasSubstr("state: emergency_stop"));
  command(1.0);
  for (const json& message : jointStates(20)) EXPECT_EQ(position(message), 0.5);  // 0.2 s of states
  EXPECT_EQ(controllerState("position_controller"), "running");
  expectLoopKeepsItsRate();

  // Released on the topic: the controller's command goes through.
  const CliResult release = cli({"topic", "pub", "/one_DOF_robot/estop", "std_msgs/Bool", "false"});
  ASSERT_EQ(release.status, 0) << release.err;
  ASSERT_TRUE(positionReaches(1.0, 1e-9));
  EXPECT_EQ(state(), "running");

  // Engaged on the topic.
  ASSERT_EQ(cli({"topic", "pub", "/one_DOF_robot/estop", "std_msgs/Bool", "true"}).status, 0);
  ASSERT_TRUE(waitFor([&] { return state() == "emergency_stop"; }));
  ASSERT_EQ(cli({"control", "estop", "off"}).status, 0);

  // The hardware's input: latched, and not released while it is active.
  script("estop\n");
  ASSERT_TRUE(waitFor([&] { return safety().value("hardware_emergency_input", false); }));
  EXPECT_EQ(state(), "emergency_stop");
  EXPECT_THAT(safety().value("reason", ""), HasSubstr("hardware input"));
  // Logged on the node, like a stop by command or topic.
  const auto nodeLog = [&] { return node_->currentOut() + node_->currentErr(); };
  EXPECT_TRUE(waitFor([&] { return nodeLog().find("emergency stop engaged by hardware input") != std::string::npos; }))
      << nodeLog();
  expectLoopKeepsItsRate();
  const CliResult refused = cli({"control", "estop", "off"});
  EXPECT_EQ(refused.status, 1);
  EXPECT_EQ(lineCount(refused.err), 1) << refused.err;
  EXPECT_THAT(refused.err, HasSubstr("input is still active"));
  script("");
  ASSERT_TRUE(waitFor([&] { return !safety().value("hardware_emergency_input", true); }));
  EXPECT_EQ(state(), "emergency_stop");  // latched until released
  ASSERT_EQ(cli({"control", "estop", "off"}).status, 0);
  command(0.25);
  ASSERT_TRUE(positionReaches(0.25, 1e-9));
  expectLoopKeepsItsRate();
}

TEST_F(SafetyOnHardware, ReadAndWriteErrorsAreProtectiveStopsRecoveredByCommand) {
  for (const std::string failure : {"fail_read", "fail_write"}) {
    SCOPED_TRACE(failure);
    command(0.5);
    ASSERT_TRUE(positionReaches(0.5, 1e-9));
    script(failure + "\n");
    ASSERT_TRUE(waitFor([&] { return state() == "protective_stop"; }));
    const std::string call = failure == "fail_read" ? "read()" : "write()";
    EXPECT_THAT(safety().value("reason", ""), HasSubstr(call + " returned an error"));
    EXPECT_EQ(controllerState("position_controller"), "failed");
    EXPECT_EQ(controllerState("joint_state_controller"), "running");  // it commands nothing
    // The diagnostics say so (published once a second).
    const CliResult diagnostics = cli({"topic", "echo", "-n", "1", "--json", "/one_DOF_robot/diagnostics"});
    ASSERT_EQ(diagnostics.status, 0) << diagnostics.err;
    const json report = json::parse(diagnostics.out);
    EXPECT_EQ(report.at("status")[0].at("name"), "/one_DOF_robot: control loop");
    EXPECT_EQ(report.at("status")[0].at("level"), 2);
    EXPECT_THAT(report.at("status")[0].at("message").get<std::string>(), HasSubstr("protective stop"));
    EXPECT_EQ(report.at("status")[2].at("name"), "/one_DOF_robot: position_controller");
    EXPECT_EQ(report.at("status")[2].at("level"), 2);

    expectLoopKeepsItsRate();  // in protective stop, the hardware still failing

    // Recovering while the hardware still fails: refused, still stopped.
    const CliResult early = cli({"control", "recover"});
    EXPECT_EQ(early.status, 1);
    EXPECT_THAT(early.err, HasSubstr("failed again"));
    EXPECT_EQ(state(), "protective_stop");

    // The stop is latched after the hardware works again, until recover.
    script("");
    ASSERT_TRUE(waitFor([&] { return !jointStates(1).empty(); }));
    EXPECT_EQ(state(), "protective_stop");
    const CliResult recovered = cli({"control", "recover"});
    ASSERT_EQ(recovered.status, 0) << recovered.err;
    EXPECT_THAT(recovered.out, HasSubstr("state: running"));
    EXPECT_EQ(controllerState("position_controller"), "running");
    command(-0.3);
    ASSERT_TRUE(positionReaches(-0.3, 1e-9));
    expectLoopKeepsItsRate();
  }
  // The summary counts the stops: two per failure (the first, and the one the
  // early recovery ran into).
  node_->signal(SIGINT);
  const CliResult ended = node_->wait(kWait_s);
  node_.reset();
  ASSERT_FALSE(ended.timed_out);
  EXPECT_THAT(ended.out, HasSubstr("safety: running at the end; 4 protective stop(s), 0 emergency stop(s)"));
}

TEST_F(SafetyOnHardware, ARefusedModeSwitchStartsNothingAndAStallOnlyOverruns) {
  script("fail_switch\n");
  ASSERT_TRUE(waitFor([&] {
    const CliResult stop = cli({"control", "stop", "position_controller"});
    return stop.status == 1 && stop.err.find("could not change its command modes") != std::string::npos;
  }));
  EXPECT_EQ(controllerState("position_controller"), "running");
  EXPECT_EQ(state(), "running");
  script("");
  expectLoopKeepsItsRate();

  // A read that takes 5 ms at 500 Hz: every cycle overruns, nothing stops;
  // `control stats` shows it in read() and the overruns, and --reset zeroes
  // them.
  const CliResult reset = cli({"control", "stats", "--reset"});
  ASSERT_EQ(reset.status, 0) << reset.err;
  EXPECT_THAT(reset.out, HasSubstr("position_controller update()"));
  script("stall_ms 5\n");
  command(0.75);
  ASSERT_TRUE(positionReaches(0.75, 1e-9));
  EXPECT_EQ(state(), "running");
  script("");
  ASSERT_TRUE(positionReaches(0.75, 1e-9));  // a cycle or more after the stall ended
  const CliResult stats = cli({"control", "stats", "--json"});
  ASSERT_EQ(stats.status, 0) << stats.err;
  const json figures = json::parse(stats.out);
  const json& loop = figures.at("loop");
  EXPECT_GE(loop.at("read").at("max").get<double>(), 0.005);
  EXPECT_GE(loop.at("overruns").get<std::uint64_t>(), 1u);
  EXPECT_EQ(loop.at("read").at("count"), loop.at("cycles"));
  EXPECT_EQ(loop.at("wakeup_latency").at("count"), loop.at("cycles"));
  EXPECT_LT(loop.at("write").at("max").get<double>(), 0.005);
  ASSERT_EQ(figures.at("controllers").size(), 2u);
  EXPECT_EQ(figures.at("controllers")[1].at("name"), "position_controller");
  EXPECT_GT(figures.at("controllers")[1].at("update").at("count").get<std::uint64_t>(), 0u);
  EXPECT_EQ(cli({"control", "list"}).status, 0);
  expectLoopKeepsItsRate();  // the stall is over
}

TEST_F(SafetyOnHardware, AHardwareThatDeactivatesIsAFaultTheNodeSurvivesAndRecovers) {
  command(0.5);
  ASSERT_TRUE(positionReaches(0.5, 1e-9));
  script("deactivate\n");
  ASSERT_TRUE(waitFor([&] { return state() == "fault"; }));
  EXPECT_THAT(safety().value("reason", ""), HasSubstr("write() returned deactivate"));
  // The node serves on; switches wait for the recovery.
  const CliResult refused = cli({"control", "stop", "position_controller"});
  EXPECT_EQ(refused.status, 1);
  EXPECT_THAT(refused.err, HasSubstr("fault"));
  EXPECT_EQ(cli({"topic", "list"}).status, 0);

  script("");
  const CliResult recovered = cli({"control", "recover"});
  ASSERT_EQ(recovered.status, 0) << recovered.err;
  EXPECT_EQ(state(), "running");
  EXPECT_EQ(controllerState("position_controller"), "running");
  command(0.9);
  ASSERT_TRUE(positionReaches(0.9, 1e-9));
  expectLoopKeepsItsRate();
}

// Hardware cannot be reset: `servoloop world reset` (Gazebo's
// reset_simulation) is refused with one error, and the robot runs on.
// A driver blocked on a device that went away: read() does not return.
// Within about a second `control safety` says fault and why, what needs a
// cycle is refused at once naming it, the robot runs on once read()
// returns, and Ctrl-C ends the node even while it does not.
TEST_F(SafetyOnHardware, AReadThatDoesNotReturnIsAFaultCommandsSeeAndCtrlCEnds) {
  script("hang\n");
  ASSERT_TRUE(waitFor([&] { return state() == "fault"; })) << node_->currentErr();
  EXPECT_THAT(safety().value("reason", ""), HasSubstr("its hardware's read() has not returned for"));
  EXPECT_THAT(node_->currentErr(), HasSubstr("robot '/one_DOF_robot': its hardware's read() has not returned"));
  const CliResult stop = cli({"control", "stop", "position_controller"});
  EXPECT_EQ(stop.status, 1);
  EXPECT_THAT(stop.err, HasSubstr("read() has not returned"));
  // Refused at once, not after the switch's wait for a cycle (10 s).
  EXPECT_LT(stop.elapsed_s, 5.0);
  EXPECT_EQ(controllerState("position_controller"), "running");

  script("");
  ASSERT_TRUE(waitFor([&] { return state() == "running"; })) << node_->currentErr();
  EXPECT_THAT(node_->currentErr(), HasSubstr("its hardware's read() returned after"));
  expectLoopKeepsItsRate();

  script("hang\n");
  ASSERT_TRUE(waitFor([&] { return state() == "fault"; }));
  node_->signal(SIGINT);
  const CliResult ended = node_->wait(kWait_s);
  EXPECT_FALSE(ended.timed_out) << ended.err;
  EXPECT_THAT(ended.err, HasSubstr("the node ends without waiting for it"));
  node_.reset();
}

TEST_F(SafetyOnHardware, AResetOfAWorldWithHardwareIsRefusedAndTheRobotRunsOn) {
  command(0.5);
  ASSERT_TRUE(positionReaches(0.5, 1e-9));
  const CliResult reset = cli({"world", "reset"});
  EXPECT_NE(reset.status, 0);
  EXPECT_THAT(reset.err, HasSubstr("hardware cannot be reset"));
  EXPECT_EQ(state(), "running");
  command(0.9);
  ASSERT_TRUE(positionReaches(0.9, 1e-9));
}

TEST_F(SafetyOnHardware, AnEmergencyStopPressedBeforeAFaultIsReleasedWhileTheLoopStands) {
  command(0.5);
  ASSERT_TRUE(positionReaches(0.5, 1e-9));
  script("estop\n");
  ASSERT_TRUE(waitFor([&] { return state() == "emergency_stop"; }));
  script("estop\ndeactivate\n");
  ASSERT_TRUE(waitFor([&] { return state() == "fault"; }));
  // The loop stands; the input is still pressed: the release is refused.
  const CliResult refused = cli({"control", "estop", "off"});
  EXPECT_EQ(refused.status, 1);
  EXPECT_THAT(refused.err, HasSubstr("input"));

  // Released on the robot while the loop stands (nothing polls it now): the
  // release reads the input itself, then recover runs the loop again.
  script("");
  const CliResult released = cli({"control", "estop", "off"});
  EXPECT_EQ(released.status, 0) << released.err;
  const CliResult recovered = cli({"control", "recover"});
  ASSERT_EQ(recovered.status, 0) << recovered.err;
  EXPECT_EQ(state(), "running");
  command(0.9);
  ASSERT_TRUE(positionReaches(0.9, 1e-9));
}

// Real hardware moves its joints whatever the description says of the links'
// masses: a moving link without <inertial> (common in descriptions written
// for hardware) keeps its joint, where a simulator leaves it out.
class MasslessLinkOnHardware : public SafetyOnHardware {
 protected:
  fs::path urdf() override {
    std::ifstream in(kOneDof / "minimal_robot_description_w_jnt_ctl.urdf");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t begin = text.find("<inertial>", text.find("<link name=\"link2\">"));
    const std::size_t end = text.find("</inertial>", begin);
    EXPECT_NE(begin, std::string::npos);
    if (begin != std::string::npos && end != std::string::npos) text.erase(begin, end + 11 - begin);
    const fs::path path = scratch() / "massless_link2.urdf";
    std::ofstream(path) << text;
    return path;
  }
};

TEST_F(MasslessLinkOnHardware, KeepsTheJointAndItsController) {
  EXPECT_EQ(controllerState("position_controller"), "running");
  command(0.5);
  ASSERT_TRUE(positionReaches(0.5, 1e-9));
}

// The seed robot simulated (bullet, paced at 5 × real time), held at 1 rad by its
// effort PID against gravity. An emergency stop sends 0 N·m (gravity swings
// the arm away), and the release brings the controller's effort back: the
// arm returns to 1 rad, held by the effort that held it before.
TEST_F(SafetyCli, InSimulationAnEmergencyStopRemovesTheHoldingEffortAndTheReleaseRestoresIt) {
  CliProcess node({"launch", (kOneDof / "one_dof_w_jnt_ctl.launch.yaml").string(), "--rtf", "5", "--pub",
                   "/one_DOF_robot/joint1_position_controller/command:=1.0"},
                  scratch());
  ASSERT_TRUE(waitForNode()) << node.currentOut();
  double holding_effort = 0.0;
  const auto settledAtOne = [&] {
    const std::vector<json> states = jointStates(1);
    if (states.empty() || std::abs(position(states[0]) - 1.0) > 1e-3) return false;
    if (std::abs(states[0].at("velocity").at(0).get<double>()) > 1e-3) return false;
    holding_effort = effort(states[0]);
    return true;
  };
  ASSERT_TRUE(waitFor(settledAtOne));
  EXPECT_GT(std::abs(holding_effort), 1.0);  // gravity needs holding

  ASSERT_EQ(cli({"control", "estop", "on"}).status, 0);
  const std::vector<json> stopped = jointStates(10);
  ASSERT_EQ(stopped.size(), 10u);
  for (const json& message : stopped) EXPECT_EQ(effort(message), 0.0);
  EXPECT_GT(std::abs(position(stopped.back()) - 1.0), 0.01);  // swinging away

  ASSERT_EQ(cli({"control", "estop", "off"}).status, 0);
  const double before = holding_effort;
  ASSERT_TRUE(waitFor(settledAtOne));
  EXPECT_NEAR(holding_effort, before, 0.05);

  node.signal(SIGINT);
  EXPECT_FALSE(node.wait(kWait_s).timed_out);
}

}  // namespace
}  // namespace servoloop::cli::testing
