// Headless runs of the seed robot through the whole node: launch file →
// backend plugin → controller plugins → SimulationLoop, with a timed command,
// recordings and the end-of-run summary. Checked against the physics of the
// one-DOF robot (link2: m = 1 kg, centre of mass d = 0.5 m from the joint,
// I_yy = 0.1 kg·m², so I = 0.1 + m·d² = 0.35 kg·m² about the joint).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "node_test_support.hpp"
#include "servoloop/node/node.hpp"

namespace {

using namespace servoloop::node;
using namespace servoloop::node_test;

constexpr const char* kCommandTopic = "/one_DOF_robot/joint1_position_controller/command";
constexpr const char* kJointStates = "/one_DOF_robot/joint_states";

struct CsvRows {
  std::string header;
  std::vector<std::vector<double>> rows;
};

CsvRows readCsv(const fs::path& file) {
  CsvRows csv;
  std::stringstream text(readFile(file));
  std::getline(text, csv.header);
  for (std::string line; std::getline(text, line);) {
    std::vector<double> row;
    std::stringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');) row.push_back(std::stod(field));
    csv.rows.push_back(row);
  }
  return csv;
}

struct RunResult {
  RunSummary summary;
  CsvRows joint_states;
  CsvRows command;
};

// Runs `launch` headless for duration_s with the command published at
// command_time_s, recording joint states and the command.
RunResult runHeadless(LaunchFile launch, double duration_s, const std::string& command_topic, double command,
                      double command_time_s) {
  TempDir dir("servoloop-node-run");
  launch.publish.push_back(makeTimedPublication(command_topic, "", command, command_time_s, "test"));
  launch.record.push_back({kJointStates, dir.path() / "joint_states.csv"});
  launch.record.push_back({command_topic, dir.path() / "command.csv"});
  NodeOptions options;
  options.duration_s = duration_s;
  options.serve_ipc = false;
  RunResult result;
  {
    Node node(launch, options);
    node.start();
    node.waitUntilDone({}, std::chrono::milliseconds(10));
    node.shutdown();
    result.summary = node.summary();
  }
  result.joint_states = readCsv(dir.path() / "joint_states.csv");
  result.command = readCsv(dir.path() / "command.csv");
  return result;
}

const JointReading& joint1(const RunSummary& summary) {
  return summary.robots.at(0).joints.at(0);
}

void expectBothControllersRunning(const RunSummary& summary) {
  ASSERT_EQ(summary.robots.size(), 1u);
  const auto& controllers = summary.robots[0].controllers;
  ASSERT_EQ(controllers.size(), 2u);
  EXPECT_EQ(controllers[0].name, "joint_state_controller");
  EXPECT_EQ(controllers[0].state, "running");
  EXPECT_EQ(controllers[1].name, "joint1_position_controller");
  EXPECT_EQ(controllers[1].type, "effort_controllers/JointPositionController");
  EXPECT_EQ(controllers[1].state, "running");
}

// What every run of the seed launch file records, whatever the backend.
void expectRecordings(const RunResult& run, double duration_s, double command_time_s) {
  // The command: one row, stamped with the simulated time it was published at.
  EXPECT_EQ(run.command.header, "time,data");
  ASSERT_EQ(run.command.rows.size(), 1u);
  EXPECT_NEAR(run.command.rows[0][0], command_time_s, 1e-9);
  EXPECT_DOUBLE_EQ(run.command.rows[0][1], 1.0);

  // Joint states at 50 Hz, none lost although the loop ran free.
  EXPECT_EQ(run.joint_states.header, "time,joint1.position,joint1.velocity,joint1.effort");
  const auto& rows = run.joint_states.rows;
  ASSERT_GE(rows.size(), static_cast<std::size_t>(duration_s * 50) - 1);
  EXPECT_LE(rows.size(), static_cast<std::size_t>(duration_s * 50) + 1);
  // Controllers start before the first physics step and first update at
  // t = 0, so the 50 Hz joint states are stamped 0.02 k.
  EXPECT_EQ(rows.front()[0], 0.0);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    ASSERT_NEAR(rows[i][0] - rows[i - 1][0], 0.02, 1e-9) << "gap after t = " << rows[i - 1][0];
  }
}

// The joint state row stamped t (50 Hz rows).
const std::vector<double>& rowAt(const CsvRows& csv, double t) {
  for (const auto& row : csv.rows) {
    if (std::abs(row[0] - t) < 1e-9) return row;
  }
  throw std::runtime_error("no joint state row at t = " + std::to_string(t));
}

TEST(NodeRun, SeedJointControllerOnMockReachesCommand) {
  ASSERT_TRUE(backendAvailable("mock")) << "the mock backend plugin is not in the build's plugin folder";
  const double duration_s = 20.0;
  const RunResult run = runHeadless(seedLaunch("mock"), duration_s, kCommandTopic, 1.0, 0.5);

  EXPECT_NEAR(run.summary.sim_time_s, duration_s, 1e-9);
  EXPECT_EQ(run.summary.cycles, 20000u);  // 20 s at the 1 ms physics step
  EXPECT_EQ(run.summary.robots.at(0).loop.control_updates, 20000u);  // update_rate 1000 Hz
  expectBothControllersRunning(run.summary);
  expectRecordings(run, duration_s, 0.5);

  // Before the command the PID holds the start position exactly (the mock has
  // no gravity). The command reaches the controller at t = 0.5 s and not a
  // control cycle earlier: the joint state of the update at 0.5 s (measured
  // before that update's effort is applied) still shows the start position,
  // the next one has moved. (node_timing_test checks the exact cycle.)
  EXPECT_EQ(rowAt(run.joint_states, 0.48)[1], 0.0);
  EXPECT_EQ(rowAt(run.joint_states, 0.5)[1], 0.0);
  EXPECT_GT(rowAt(run.joint_states, 0.52)[1], 0.0);

  // Closed loop (no gravity, no damping): 0.35 q'' = 10 e + 10 ∫e + 10 ė. Its
  // slowest poles, from 10 s² + 10 s + 10, have real part -0.5 1/s: the ~19 s
  // after the command leave e^-9.5 ≈ 7e-5 of an O(1) error, well under 1 mrad.
  EXPECT_NEAR(joint1(run.summary).position, 1.0, 1e-3);
  EXPECT_NEAR(joint1(run.summary).velocity, 0.0, 1e-3);
}

TEST(NodeRun, SeedJointControllerOnBulletReachesCommand) {
  if (!backendAvailable("bullet")) GTEST_SKIP() << "the bullet backend plugin is not built";
  const double duration_s = 20.0;
  const RunResult run = runHeadless(seedLaunch("bullet"), duration_s, kCommandTopic, 1.0, 0.5);

  EXPECT_NEAR(run.summary.sim_time_s, duration_s, 1e-9);
  EXPECT_EQ(run.summary.cycles, 20000u);
  expectBothControllersRunning(run.summary);
  expectRecordings(run, duration_s, 0.5);

  // Bullet adds gravity (the link stands upright at q = 0, so gravity pushes
  // it away from the command with m·g·d·sin q = 4.13 N·m at 1 rad) and the
  // URDF's damping of 1 N·m·s/rad. The PID's integral term takes over the
  // gravity load (4.13 N·m < i_clamp 10), so the steady state is the command
  // itself. Linearised at 1 rad the loop is 0.35 s³ + 11 s² + (10 - 2.65) s +
  // 10 = 0, slowest poles -0.33 ± 0.9i 1/s: from the first overshoot (≈ 0.65
  // rad at ≈ 2.4 s) 17.6 s of decay leave 0.65·e^-5.8 ≈ 2e-3 rad, so 5 mrad
  // holds with margin (a 30 s run ends within 1e-4 rad of the command).
  EXPECT_NEAR(joint1(run.summary).position, 1.0, 5e-3);
  EXPECT_NEAR(joint1(run.summary).velocity, 0.0, 5e-3);
  // The joint stays inside its URDF limits [0, 2] rad throughout.
  for (const auto& row : run.joint_states.rows) {
    ASSERT_GE(row[1], -1e-3);
    ASSERT_LE(row[1], 2.0 + 1e-3);
  }
}

// Raw PD of the seed tutorial, effort = kp·(cmd - q) - kv·q̇ with kp = 10,
// kv = 3, on the continuous joint (no limits, no damping). At rest the PD
// effort balances gravity, kp·(1 - q) + m·g·d·sin q = 0 (gravity pushes the
// upright link away from q = 0), so the robot settles past the command: the
// root of that equation, found here by bisection, is the independent reference.
double rawPdSteadyState(double command) {
  const double kp = 10.0;
  const double gravity_torque = 1.0 * 9.81 * 0.5;
  auto residual = [&](double q) { return kp * (command - q) + gravity_torque * std::sin(q); };
  double low = command;        // residual > 0 here
  double high = command + 1.0; // residual < 0 here
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (low + high);
    (residual(mid) > 0.0 ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

TEST(NodeRun, RawPdOnBulletSettlesWhereGravityBalancesThePd) {
  if (!backendAvailable("bullet")) GTEST_SKIP() << "the bullet backend plugin is not built";
  LaunchFile launch = loadLaunchFile(oneDofDir() / "one_dof_raw_pd.launch.yaml");
  const RunResult run = runHeadless(launch, 20.0, "/one_DOF_robot/minimal_joint_controller/pos_cmd", 1.0, 0.0);
  const double expected = rawPdSteadyState(1.0);
  EXPECT_NEAR(expected, 1.49, 0.01);  // sanity of the reference itself
  // Linearised at the rest point: 0.35 s² + 3 s + (10 - 4.905 cos q) = 0, poles
  // at ≈ -4.3 ± 2.2 i: after 20 s nothing of the transient is left, so the
  // tolerance only covers the 100 Hz controller's discretisation.
  EXPECT_NEAR(joint1(run.summary).position, expected, 2e-3);
  ASSERT_EQ(run.summary.robots.at(0).controllers.size(), 2u);
  EXPECT_EQ(run.summary.robots[0].controllers[1].state, "running");
}

TEST(NodeRun, RawPdOnMockReachesTheCommand) {
  ASSERT_TRUE(backendAvailable("mock"));
  LaunchFile launch = loadLaunchFile(oneDofDir() / "one_dof_raw_pd.launch.yaml");
  launch.world.backend = "mock";
  const RunResult run = runHeadless(launch, 10.0, "/one_DOF_robot/minimal_joint_controller/pos_cmd", 1.0, 0.0);
  // No gravity: 0.35 q'' + 3 q' + 10 (q - 1) = 0, poles ≈ -4.3 ± 3.1 i; after
  // 10 s the error is below e^-40.
  EXPECT_NEAR(joint1(run.summary).position, 1.0, 1e-6);
}

TEST(NodeRun, ControllerThatFailsToLoadIsReportedAndTheRunGoesOn) {
  ASSERT_TRUE(backendAvailable("mock"));
  LaunchFile launch = seedLaunch("mock");
  launch.robots[0].controllers.push_back("no_such_controller");
  NodeOptions options;
  options.duration_s = 0.1;
  options.serve_ipc = false;
  Node node(launch, options);
  node.start();
  node.waitUntilDone({}, std::chrono::milliseconds(5));
  node.shutdown();
  const RunSummary summary = node.summary();
  EXPECT_NEAR(summary.sim_time_s, 0.1, 1e-9);
  expectBothControllersRunning(summary);
}

// waitUntilDone() returns when the robots' loops end, not at its next tick: a
// free-running 1 s run of the mock robot takes milliseconds, far below the
// one-minute tick given here (which the old polling would have waited out).
TEST(NodeRun, WaitUntilDoneReturnsWhenTheRunEndsNotAtTheNextTick) {
  ASSERT_TRUE(backendAvailable("mock"));
  NodeOptions options;
  options.duration_s = 1.0;
  options.serve_ipc = false;
  Node node(seedLaunch("mock"), options);
  node.start();
  const auto before = std::chrono::steady_clock::now();
  node.waitUntilDone({}, std::chrono::minutes(1));
  const double waited_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count();
  node.shutdown();
  EXPECT_LT(waited_s, 30.0);  // half the tick: woken by the loop's end, not by the tick
  EXPECT_NEAR(node.summary().sim_time_s, 1.0, 1e-9);
}

TEST(NodeRun, BackendThatDoesNotExistIsAConfigError) {
  NodeOptions options;
  options.duration_s = 0.1;
  options.serve_ipc = false;
  try {
    Node node(seedLaunch("warp_drive"), options);
    FAIL() << "no error";
  } catch (const servoloop::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("backend 'warp_drive'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--backend"), std::string::npos) << e.what();
  }
}

TEST(NodeRun, UpdateRateThatIsNoMultipleOfTheStepIsAConfigError) {
  LaunchFile launch = seedLaunch("mock");
  launch.controller_manager.update_rate_hz = 300.0;  // 3.33 ms is not a multiple of 1 ms
  NodeOptions options;
  options.serve_ipc = false;
  try {
    Node node(launch, options);
    FAIL() << "no error";
  } catch (const servoloop::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("controller_manager.update_rate 300 Hz"), std::string::npos) << e.what();
  }
}

}  // namespace
