// When things happen in a node's simulated time: the launch file's controllers
// start before the first physics step, so a publication at t = 0 is seen by
// their first update (at t = 0, with the nominal period, whatever the
// controller's rate); stamps are exact decimal multiples of the physics step;
// and, on bullet, what the URDF velocity limit does (and does not do) with the
// effort interface, as docs/launch_files.md describes it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "node_test_support.hpp"
#include "servoloop/node/node.hpp"

namespace {

using namespace servoloop::node;
using namespace servoloop::node_test;

constexpr const char* kCommandTopic = "/one_DOF_robot/joint1_position_controller/command";
constexpr const char* kStateTopic = "/one_DOF_robot/joint1_position_controller/state";
constexpr const char* kJointStates = "/one_DOF_robot/joint_states";

// A recording: the header's column names, and every row both as text fields
// and as numbers.
struct Recording {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> text;
  std::vector<std::vector<double>> rows;

  std::size_t column(const std::string& name) const {
    const auto it = std::find(columns.begin(), columns.end(), name);
    if (it == columns.end()) throw std::runtime_error("no column '" + name + "'");
    return static_cast<std::size_t>(it - columns.begin());
  }
};

std::vector<std::string> splitCommas(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  for (std::string field; std::getline(stream, field, ',');) fields.push_back(field);
  return fields;
}

Recording readRecording(const fs::path& file) {
  Recording recording;
  std::stringstream text(readFile(file));
  std::string line;
  std::getline(text, line);
  recording.columns = splitCommas(line);
  while (std::getline(text, line)) {
    recording.text.push_back(splitCommas(line));
    std::vector<double> row;
    for (const std::string& field : recording.text.back()) row.push_back(std::stod(field));
    recording.rows.push_back(row);
  }
  return recording;
}

// Runs `launch` headless on its backend for duration_s with `command` published
// on `command_topic` at t = 0, recording `topics`.
std::map<std::string, Recording> runRecording(LaunchFile launch, double duration_s, const std::string& command_topic,
                                              const std::vector<std::string>& topics) {
  TempDir dir("servoloop-node-timing");
  launch.publish.push_back(makeTimedPublication(command_topic, "", 1.0, 0.0, "test"));
  std::map<std::string, fs::path> files;
  for (std::size_t i = 0; i < topics.size(); ++i) {
    files[topics[i]] = dir.path() / ("topic" + std::to_string(i) + ".csv");
    launch.record.push_back({topics[i], files[topics[i]]});
  }
  NodeOptions options;
  options.duration_s = duration_s;
  options.serve_ipc = false;
  {
    Node node(launch, options);
    node.start();
    node.waitUntilDone({}, std::chrono::milliseconds(5));
    node.shutdown();
  }
  std::map<std::string, Recording> recordings;
  for (const auto& [topic, file] : files) recordings[topic] = readRecording(file);
  return recordings;
}

// Milliseconds as the shortest decimal text: 20 -> "0.02", 3000 -> "3.0".
std::string millisecondsText(std::uint64_t ms) {
  std::string fraction = std::to_string(ms % 1000);
  fraction.insert(0, 3 - fraction.size(), '0');
  while (fraction.size() > 1 && fraction.back() == '0') fraction.pop_back();
  return std::to_string(ms / 1000) + "." + fraction;
}

TEST(NodeTiming, PublicationAtTimeZeroIsSeenByTheFirstControlUpdate) {
  ASSERT_TRUE(backendAvailable("mock"));
  const auto recordings = runRecording(seedLaunch("mock"), 0.1, kCommandTopic, {kCommandTopic, kStateTopic, kJointStates});

  // The command is stamped with the time it was published at.
  const Recording& command = recordings.at(kCommandTopic);
  ASSERT_EQ(command.text.size(), 1u);
  EXPECT_EQ(command.text[0][0], "0.0");
  EXPECT_EQ(command.text[0][1], "1.0");

  // The position controller's state (published on its 1st, 11th, ... update):
  // its first update is at t = 0, with the nominal 1 ms period, and already
  // has the command as its setpoint; the joint is still at its start (0), so
  // the PID pushes with error 1.
  const Recording& state = recordings.at(kStateTopic);
  ASSERT_GE(state.rows.size(), 2u);
  EXPECT_EQ(state.rows[0][0], 0.0);
  EXPECT_EQ(state.rows[0][state.column("set_point")], 1.0);
  EXPECT_EQ(state.rows[0][state.column("process_value")], 0.0);
  EXPECT_EQ(state.rows[0][state.column("error")], 1.0);
  EXPECT_EQ(state.rows[0][state.column("time_step")], 0.001);
  EXPECT_GT(state.rows[0][state.column("command")], 0.0);
  EXPECT_EQ(state.rows[1][0], 0.01);

  // Joint states from t = 0 on (the first update publishes), every 20 ms.
  const Recording& joint_states = recordings.at(kJointStates);
  ASSERT_EQ(joint_states.rows.size(), 5u);  // 0, 0.02, ..., 0.08
  EXPECT_EQ(joint_states.rows[0][0], 0.0);
  EXPECT_EQ(joint_states.rows[0][joint_states.column("joint1.position")], 0.0);
  EXPECT_GT(joint_states.rows[1][joint_states.column("joint1.position")], 0.0);
}

TEST(NodeTiming, AControllerAtALowerRateAlsoFirstUpdatesAtTimeZero) {
  ASSERT_TRUE(backendAvailable("mock"));
  LaunchFile launch = loadLaunchFile(oneDofDir() / "one_dof_raw_pd.launch.yaml");
  launch.world.backend = "mock";
  const std::string pd = "/one_DOF_robot/minimal_joint_controller/";
  const auto recordings = runRecording(launch, 0.05, pd + "pos_cmd", {pd + "jnt_trq"});

  // The raw PD runs every 10th 1 ms cycle: updates at 0, 10, 20, 30, 40 ms.
  // Its first one already sees the command: effort = kp·(1 − 0) − kv·0 = 10.
  const Recording& effort = recordings.at(pd + "jnt_trq");
  ASSERT_EQ(effort.rows.size(), 5u);
  for (std::size_t i = 0; i < effort.rows.size(); ++i) {
    EXPECT_EQ(effort.text[i][0], millisecondsText(10 * i)) << "update " << i;
  }
  EXPECT_EQ(effort.rows[0][1], 10.0);
  EXPECT_LT(effort.rows[1][1], 10.0);  // the joint has started to move
}

TEST(NodeTiming, StampsAreExactDecimalMultiplesOfTheStep) {
  ASSERT_TRUE(backendAvailable("mock"));
  const double duration_s = 5.0;
  const auto recordings = runRecording(seedLaunch("mock"), duration_s, kCommandTopic, {kJointStates});
  const Recording& joint_states = recordings.at(kJointStates);
  ASSERT_EQ(joint_states.rows.size(), 250u);
  // Row k is stamped 20·k ms, and prints as that decimal: 3.14, never
  // 3.1400000000000001 (steps × 0.001 in doubles would give 28 such rows).
  for (std::size_t k = 0; k < joint_states.rows.size(); ++k) {
    ASSERT_EQ(joint_states.text[k][0], millisecondsText(20 * k)) << "row " << k;
  }
}

// The seed robot on bullet with a 1 rad command at t = 0: gravity pulls the
// upright link towards the command, and the URDF velocity limit (0.5 rad/s)
// with the effort interface only saturates the effort — it cuts the effort
// pushing faster, it never brakes — so the joint runs well past its limit.
// Soft limits (here from YAML joint_limits) brake it: above the limit the
// effort is bounded by −k_velocity·(v − 0.5), so gravity's at most 4.9 N·m
// can only hold v ≈ 0.5 + 4.9 / k_velocity.
double peakVelocity(const Recording& joint_states) {
  double peak = 0.0;
  const std::size_t velocity = joint_states.column("joint1.velocity");
  for (const auto& row : joint_states.rows) peak = std::max(peak, std::abs(row[velocity]));
  return peak;
}

TEST(NodeTiming, EffortInterfaceVelocityLimitDoesNotBrakeButSoftLimitsDo) {
  if (!backendAvailable("bullet")) GTEST_SKIP() << "the bullet backend plugin is not built";
  const double without_soft_limits =
      peakVelocity(runRecording(seedLaunch("bullet"), 3.0, kCommandTopic, {kJointStates}).at(kJointStates));
  EXPECT_GT(without_soft_limits, 1.0);  // docs/launch_files.md: about 1.2 rad/s

  TempDir dir("servoloop-node-soft-limits");
  const fs::path limits = dir.path() / "soft_limits.yaml";
  std::ofstream(limits) << "one_DOF_robot:\n  joint_limits:\n    joint1:\n      has_soft_limits: true\n"
                           "      k_position: 20.0\n      k_velocity: 50.0\n"
                           "      soft_lower_limit: 0.0\n      soft_upper_limit: 2.0\n";
  LaunchFile launch = seedLaunch("bullet");
  launch.robots.at(0).params.push_back(ParameterFile{limits, "/", "", ""});
  const double with_soft_limits =
      peakVelocity(runRecording(launch, 3.0, kCommandTopic, {kJointStates}).at(kJointStates));
  EXPECT_LT(with_soft_limits, 0.5 + 4.905 / 50.0 + 0.02);
}

}  // namespace
