// `servoloop spawner` against a fake node: ros_control's spawner semantics
// (ros_control_semantics.md "Spawner"), plus a non-zero exit when the node
// never appears.
#include <csignal>
#include <fstream>
#include <string>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_client_support.hpp"

namespace servoloop::cli::testing {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using nlohmann::json;

class SpawnerTest : public ::testing::Test {
 protected:
  ScopedRunDir run_dir_;
};

TEST_F(SpawnerTest, LoadsEachThenStartsAllInOneStrictSwitch) {
  FakeNode node("/one_DOF_robot");
  const CliResult result = runCli(
      {"spawner", "--namespace", "/one_DOF_robot", "joint_state_controller",
       "joint1_position_controller"},
      run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_THAT(node.ops(), ElementsAre("control.load", "control.load", "control.switch"));
  const auto loads = node.requestsFor("control.load");
  EXPECT_EQ(loads[0]["name"], "joint_state_controller");
  EXPECT_EQ(loads[1]["name"], "joint1_position_controller");
  const auto switch_request = node.requestsFor("control.switch").at(0);
  EXPECT_EQ(switch_request["start"],
            json({"joint_state_controller", "joint1_position_controller"}));
  EXPECT_EQ(switch_request["stop"], json::array());
  EXPECT_EQ(switch_request["strictness"], "strict");
  EXPECT_THAT(result.out,
              HasSubstr("Started controllers: joint_state_controller, joint1_position_controller"));
}

TEST_F(SpawnerTest, AFailedLoadIsReportedAndSkippedAndTheRestStartTogether) {
  FakeNode node("/one_DOF_robot");
  node.failWhen("control.load", "joint9_controller",
                "no parameter '/one_DOF_robot/joint9_controller/type': add the controller to a "
                "YAML file loaded with `servoloop param load`");
  const CliResult result =
      runCli({"spawner", "-N", "one_DOF_robot", "a", "joint9_controller", "b"}, run_dir_.scratch());
  EXPECT_NE(result.status, 0);
  EXPECT_THAT(result.err, HasSubstr("failed to load 'joint9_controller': no parameter "
                                    "'/one_DOF_robot/joint9_controller/type'"));
  EXPECT_EQ(lineCount(result.err), 1) << result.err;
  EXPECT_THAT(node.ops(),
              ElementsAre("control.load", "control.load", "control.load", "control.switch"));
  EXPECT_EQ(node.requestsFor("control.switch").at(0)["start"], json({"a", "b"}));
}

TEST_F(SpawnerTest, StoppedOnlyLoads) {
  FakeNode node("/one_DOF_robot");
  const CliResult result =
      runCli({"spawner", "--stopped", "-N", "/one_DOF_robot", "a", "b"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_THAT(node.ops(), ElementsAre("control.load", "control.load"));
}

TEST_F(SpawnerTest, YamlArgumentsAreLoadedIntoParametersFirst) {
  FakeNode node("/one_DOF_robot");
  const auto yaml = run_dir_.scratch() / "ctl.yaml";
  std::ofstream(yaml) << "one_DOF_robot:\n  a: {type: joint_state_controller/JointStateController}\n";
  const CliResult result =
      runCli({"spawner", "-N", "/one_DOF_robot", "a", yaml.string()}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_THAT(node.ops(), ElementsAre("param.load", "control.load", "control.switch"));
  const auto load = node.requestsFor("param.load").at(0);
  EXPECT_EQ(load["file"], yaml.string());
  EXPECT_EQ(load["namespace"], "/");
  EXPECT_EQ(node.requestsFor("control.load").at(0)["name"], "a");
}

TEST_F(SpawnerTest, AFailedSwitchIsNonZeroWithTheNodesMessage) {
  FakeNode node("/one_DOF_robot");
  node.on("control.switch", [](const json&, auto&) -> json {
    return {{"ok", false},
            {"error", "resource conflict: joint1 claimed by 'a' and 'b' (EffortJointInterface)"}};
  });
  const CliResult result = runCli({"spawner", "-N", "/one_DOF_robot", "a", "b"}, run_dir_.scratch());
  EXPECT_NE(result.status, 0);
  EXPECT_THAT(result.err, HasSubstr("resource conflict: joint1 claimed by 'a' and 'b'"));
}

TEST_F(SpawnerTest, NodeThatNeverAppearsFailsAfterTheTimeout) {
  const CliResult result =
      runCli({"spawner", "--timeout", "0.5", "-N", "/one_DOF_robot", "a"}, run_dir_.scratch());
  EXPECT_NE(result.status, 0);
  EXPECT_FALSE(result.timed_out);
  EXPECT_GE(result.elapsed_s, 0.5);
  EXPECT_LT(result.elapsed_s, 10.0);
  EXPECT_THAT(result.err, HasSubstr("no servoloop node for namespace '/one_DOF_robot'"));
  EXPECT_THAT(result.err, HasSubstr("servoloop launch"));
  EXPECT_EQ(lineCount(result.err), 1) << result.err;
}

TEST_F(SpawnerTest, WaitsForANodeThatStartsLater) {
  CliProcess spawner({"spawner", "--timeout", "20", "-N", "/one_DOF_robot", "a"},
                     run_dir_.scratch());
  // The node comes up only once the spawner says it is waiting for it.
  ASSERT_TRUE(spawner.waitForOutput("waiting for the servoloop node of namespace '/one_DOF_robot'", 20.0))
      << spawner.currentOut() << spawner.currentErr();
  FakeNode node("/one_DOF_robot");
  const CliResult result = spawner.wait(20.0);
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_THAT(node.ops(), ElementsAre("control.load", "control.switch"));
}

TEST_F(SpawnerTest, UnloadOnKillStopsThenUnloadsInReverseOrderOnSigterm) {
  FakeNode node("/one_DOF_robot");
  CliProcess spawner({"spawner", "--unload-on-kill", "-N", "/one_DOF_robot", "a", "b", "c"},
                     run_dir_.scratch());
  ASSERT_TRUE(spawner.waitForOutput("Spawner running", 10.0)) << spawner.currentOut();
  EXPECT_THAT(node.ops(), ElementsAre("control.load", "control.load", "control.load",
                                      "control.switch"));
  spawner.signal(SIGTERM);
  const CliResult result = spawner.wait(10.0);
  ASSERT_EQ(result.status, 0) << result.err;
  const auto requests = node.requests();
  ASSERT_EQ(requests.size(), 8u);
  EXPECT_EQ(requests[4]["op"], "control.switch");
  EXPECT_EQ(requests[4]["stop"], json({"a", "b", "c"}));
  EXPECT_EQ(requests[4]["start"], json::array());
  EXPECT_EQ(requests[4]["strictness"], "strict");
  EXPECT_EQ(requests[5]["op"], "control.unload");
  EXPECT_EQ(requests[5]["name"], "c");
  EXPECT_EQ(requests[6]["name"], "b");
  EXPECT_EQ(requests[7]["name"], "a");
}

TEST_F(SpawnerTest, UnloadOnKillAlsoEndsOnSigint) {
  FakeNode node("/one_DOF_robot");
  CliProcess spawner({"spawner", "--unload-on-kill", "--stopped", "-N", "/one_DOF_robot", "a"},
                     run_dir_.scratch());
  ASSERT_TRUE(spawner.waitForOutput("Spawner running", 10.0));
  spawner.signal(SIGINT);
  const CliResult result = spawner.wait(10.0);
  ASSERT_EQ(result.status, 0) << result.err;
  // Never started, so nothing to stop: only the unload.
  EXPECT_THAT(node.ops(), ElementsAre("control.load", "control.unload"));
}

TEST_F(SpawnerTest, NoControllerArgumentIsAUsageError) {
  const CliResult result = runCli({"spawner", "-N", "/x"}, run_dir_.scratch());
  EXPECT_NE(result.status, 0);
  EXPECT_EQ(lineCount(result.err), 1) << result.err;
  EXPECT_THAT(result.err, HasSubstr("spawner"));
}

}  // namespace
}  // namespace servoloop::cli::testing
