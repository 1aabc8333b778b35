// The follow_joint_trajectory action from the command line, against a real
// node running the seed robot (bullet) with an effort trajectory controller:
//   servoloop action list
//   servoloop action send NAME control_msgs/FollowJointTrajectory GOAL [--json]
// A goal that is followed succeeds (exit 0) with feedback on the way; one
// whose path tolerance cannot be held is aborted with
// PATH_TOLERANCE_VIOLATED (-4, exit 1); one naming a joint the controller
// lacks is rejected with INVALID_JOINTS (-2); Ctrl-C cancels a running goal
// (exit 2). The node serves on after each.
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_client_support.hpp"
#include "wait_until.hpp"

namespace servoloop::cli::testing {
namespace {

using ::testing::HasSubstr;
using nlohmann::json;

const char* const kAction = "/one_DOF_robot/arm_controller/follow_joint_trajectory";
const char* const kType = "control_msgs/FollowJointTrajectory";

std::vector<json> jsonLines(const std::string& text) {
  std::vector<json> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.front() == '{') lines.push_back(json::parse(line));
  }
  return lines;
}

class TrajectoryAction : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto& dir = run_dir_.scratch();
    std::ofstream(dir / "jtc.yaml") << "one_DOF_robot:\n"
                                       "  arm_controller:\n"
                                       "    type: effort_controllers/JointTrajectoryController\n"
                                       "    joints: [joint1]\n"
                                       "    gains: {joint1: {p: 200, d: 20}}\n"
                                       "    stop_trajectory_duration: 0.2\n"
                                       "    action_monitor_rate: 20\n";
    std::ofstream(dir / "jtc.launch.yaml")
        << "world: {backend: bullet, time_step: 0.001, real_time_factor: 2.0}\n"
           "robots:\n"
           "  - urdf: " << SERVOLOOP_SOURCE_DIR << "/robots/one_dof/minimal_robot_description_w_jnt_ctl.urdf\n"
           "    params: [jtc.yaml]\n"
           "    controllers: [arm_controller]\n";
    launch_ = std::make_unique<CliProcess>(std::vector<std::string>{"launch", (dir / "jtc.launch.yaml").string()}, dir);
    // Up once its socket answers.
    ASSERT_TRUE(servoloop::testing::waitUntil(
        [&] { return runCli({"action", "list"}, run_dir_.scratch(), 10.0).status == 0; }, std::chrono::seconds(60)))
        << launch_->currentErr();
  }
  void TearDown() override {
    launch_->signal(SIGINT);
    EXPECT_EQ(launch_->wait(30.0).status, 0) << launch_->currentErr();
  }
  CliResult send(const std::string& goal, bool json_output = true) {
    std::vector<std::string> args = {"action", "send", kAction, kType, goal};
    if (json_output) args.push_back("--json");
    return runCli(args, run_dir_.scratch(), 60.0);
  }

  ScopedRunDir run_dir_;
  std::unique_ptr<CliProcess> launch_;
};

TEST_F(TrajectoryAction, ListSucceedAbortRejectAndCancel) {
  const CliResult list = runCli({"action", "list"}, run_dir_.scratch());
  ASSERT_EQ(list.status, 0) << list.err;
  EXPECT_THAT(list.out, HasSubstr(std::string(kAction) + "  " + kType));

  // 0 → 0.4 rad in 1.5 s, well below the joint's 0.5 rad/s limit: followed.
  const CliResult ok = send(
      "{trajectory: {joint_names: [joint1], points: [{positions: [0.4], velocities: [0], time_from_start: 1.5}]}, "
      "goal_tolerance: [{name: joint1, position: 0.05}], goal_time_tolerance: 1.0}");
  ASSERT_EQ(ok.status, 0) << ok.out << ok.err;
  const std::vector<json> events = jsonLines(ok.out);
  ASSERT_GE(events.size(), 3u) << ok.out;  // feedback on the way, then the result
  EXPECT_TRUE(events.front().contains("feedback"));
  EXPECT_EQ(events.front()["feedback"]["joint_names"], json({"joint1"}));
  EXPECT_EQ(events.back()["state"], "SUCCEEDED");
  EXPECT_EQ(events.back()["result"]["error_code"], 0);

  // 1 rad in 0.5 s needs 3.75 rad/s: the joint's 0.5 rad/s limit leaves it
  // behind, past a 0.01 rad path tolerance.
  const CliResult aborted = send(
      "{trajectory: {joint_names: [joint1], points: [{positions: [1.4], time_from_start: 0.5}]}, "
      "path_tolerance: [{name: joint1, position: 0.01}]}",
      false);
  EXPECT_EQ(aborted.status, 1) << aborted.out << aborted.err;
  EXPECT_THAT(aborted.out, HasSubstr("error_code: -4"));
  EXPECT_THAT(aborted.out, HasSubstr("state: ABORTED"));

  const CliResult rejected =
      send("{trajectory: {joint_names: [elbow], points: [{positions: [1.0], time_from_start: 1.0}]}}");
  EXPECT_EQ(rejected.status, 1);
  const std::vector<json> rejection = jsonLines(rejected.out);
  ASSERT_FALSE(rejection.empty()) << rejected.out << rejected.err;
  EXPECT_EQ(rejection.back()["state"], "REJECTED");
  EXPECT_EQ(rejection.back()["result"]["error_code"], -2);
  EXPECT_THAT(rejection.back()["result"]["error_string"].get<std::string>(), HasSubstr("'elbow'"));

  // A slow goal, canceled with Ctrl-C once its feedback shows it running.
  CliProcess slow({"action", "send", kAction, kType,
                   "{trajectory: {joint_names: [joint1], points: [{positions: [1.0], time_from_start: 600}]}}",
                   "--json"},
                  run_dir_.scratch());
  ASSERT_TRUE(slow.waitForOutput("feedback", 30.0)) << slow.currentErr();
  slow.signal(SIGINT);
  const auto canceled = slow.wait(30.0);
  EXPECT_EQ(canceled.status, 2) << canceled.out << canceled.err;
  EXPECT_EQ(jsonLines(canceled.out).back()["state"], "CANCELED");

  // The bad goal text is one error, and the node serves on.
  const CliResult malformed = send("{trajectory: {points: [{positions: [x]}]}}");
  EXPECT_EQ(malformed.status, 1);
  EXPECT_THAT(malformed.err, HasSubstr("points[0].positions[0]"));
  EXPECT_EQ(runCli({"action", "list", "--json"}, run_dir_.scratch()).status, 0);
}

}  // namespace
}  // namespace servoloop::cli::testing
