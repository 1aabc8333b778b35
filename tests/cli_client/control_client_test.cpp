// `servoloop control ...` (the commands that need a node) against a fake node,
// and how every client command finds its node.
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_client_support.hpp"

namespace servoloop::cli::testing {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using nlohmann::json;

class ControlTest : public ::testing::Test {
 protected:
  ScopedRunDir run_dir_;
};

json twoControllers() {
  return json::parse(R"([
    {"name": "joint_state_controller", "type": "joint_state_controller/JointStateController",
     "state": "running",
     "claimed_resources": [{"hardware_interface": "JointStateInterface", "resources": []}]},
    {"name": "joint1_position_controller", "type": "effort_controllers/JointPositionController",
     "state": "stopped",
     "claimed_resources": [{"hardware_interface": "EffortJointInterface", "resources": ["joint1"]}]}
  ])");
}

TEST_F(ControlTest, ListPrintsNameTypeStateAndClaims) {
  FakeNode node("/one_DOF_robot");
  node.on("control.list", [](const json&, auto&) -> json { return {{"controllers", twoControllers()}}; });
  const CliResult result = runCli({"control", "list"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(result.out,
            "joint_state_controller - joint_state_controller/JointStateController ( running )\n"
            "    JointStateInterface: (no resources)\n"
            "joint1_position_controller - effort_controllers/JointPositionController ( stopped )\n"
            "    EffortJointInterface: joint1\n");
}

TEST_F(ControlTest, ListJsonIsTheControllersArray) {
  FakeNode node("/one_DOF_robot");
  node.on("control.list", [](const json&, auto&) -> json { return {{"controllers", twoControllers()}}; });
  const CliResult result = runCli({"control", "list", "--json", "-N", "/one_DOF_robot"},
                                  run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(json::parse(result.out), twoControllers());
}

TEST_F(ControlTest, ListJointsTextAndJson) {
  FakeNode node("/one_DOF_robot");
  const json joints = json::parse(
      R"([{"name": "joint1", "interfaces": ["JointStateInterface", "EffortJointInterface"]}])");
  node.on("control.list_joints", [joints](const json&, auto&) -> json { return {{"joints", joints}}; });
  CliResult result = runCli({"control", "list-joints"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(result.out, "joint1: JointStateInterface, EffortJointInterface\n");
  result = runCli({"control", "list-joints", "--json"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(json::parse(result.out), joints);
}

TEST_F(ControlTest, LoadAndUnloadSendOneRequestPerName) {
  FakeNode node("/one_DOF_robot");
  CliResult result = runCli({"control", "load", "a", "b"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  result = runCli({"control", "unload", "b"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  const auto requests = node.requests();
  ASSERT_EQ(requests.size(), 3u);
  EXPECT_EQ(requests[0], json({{"id", requests[0]["id"]}, {"op", "control.load"}, {"name", "a"}}));
  EXPECT_EQ(requests[1]["name"], "b");
  EXPECT_EQ(requests[2]["op"], "control.unload");
}

TEST_F(ControlTest, NodeErrorIsRelayedAsOneLine) {
  FakeNode node("/one_DOF_robot");
  node.failWhen("control.unload", "a", "controller 'a' is running; stop it first");
  const CliResult result = runCli({"control", "unload", "a"}, run_dir_.scratch());
  EXPECT_EQ(result.status, 1);
  EXPECT_EQ(result.err, "servoloop control unload: error: controller 'a' is running; stop it first\n");
}

TEST_F(ControlTest, StartAndStopAreStrictSwitches) {
  FakeNode node("/one_DOF_robot");
  ASSERT_EQ(runCli({"control", "start", "a", "b"}, run_dir_.scratch()).status, 0);
  ASSERT_EQ(runCli({"control", "stop", "c"}, run_dir_.scratch()).status, 0);
  const auto switches = node.requestsFor("control.switch");
  ASSERT_EQ(switches.size(), 2u);
  EXPECT_EQ(switches[0]["start"], json({"a", "b"}));
  EXPECT_EQ(switches[0]["stop"], json::array());
  EXPECT_EQ(switches[0]["strictness"], "strict");
  EXPECT_EQ(switches[1]["stop"], json({"c"}));
  EXPECT_EQ(switches[1]["start"], json::array());
}

TEST_F(ControlTest, SwitchPassesEveryField) {
  FakeNode node("/one_DOF_robot");
  const CliResult result =
      runCli({"control", "switch", "--start", "a", "b", "--stop", "c", "--strictness",
              "best_effort", "--start-asap", "--timeout", "2.5"},
             run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  const auto request = node.requestsFor("control.switch").at(0);
  EXPECT_EQ(request["start"], json({"a", "b"}));
  EXPECT_EQ(request["stop"], json({"c"}));
  EXPECT_EQ(request["strictness"], "best_effort");
  EXPECT_EQ(request["start_asap"], true);
  EXPECT_DOUBLE_EQ(request["timeout"].get<double>(), 2.5);
}

TEST_F(ControlTest, BadStrictnessIsAUsageErrorBeforeAnyRequest) {
  FakeNode node("/one_DOF_robot");
  const CliResult result =
      runCli({"control", "switch", "--start", "a", "--strictness", "bogus"}, run_dir_.scratch());
  EXPECT_NE(result.status, 0);
  EXPECT_EQ(lineCount(result.err), 1) << result.err;
  EXPECT_THAT(result.err, HasSubstr("--strictness"));
  EXPECT_TRUE(node.requests().empty());
}

TEST_F(ControlTest, ReloadLibrariesForceKill) {
  FakeNode node("/one_DOF_robot");
  ASSERT_EQ(runCli({"control", "reload-libraries", "--force-kill"}, run_dir_.scratch()).status, 0);
  EXPECT_EQ(node.requestsFor("control.reload_libraries").at(0)["force_kill"], true);
}

TEST_F(ControlTest, GainsSendsTheControllerThePidAndOnlyTheGainsGiven) {
  FakeNode node("/one_DOF_robot");
  node.on("control.gains", [](const json&, auto&) -> json { return {{"pids", json::array()}}; });
  ASSERT_EQ(runCli({"control", "gains", "arm"}, run_dir_.scratch()).status, 0);
  const CliResult set = runCli({"control", "gains", "arm", "--pid", "gains/j1", "--i", "2", "--i-clamp-max", "3",
                                "--antiwindup", "false"},
                               run_dir_.scratch());
  ASSERT_EQ(set.status, 0) << set.err;
  const auto requests = node.requestsFor("control.gains");
  ASSERT_EQ(requests.size(), 2u);
  EXPECT_EQ(requests[0], json({{"id", requests[0]["id"]}, {"op", "control.gains"}, {"controller", "arm"}}));
  EXPECT_EQ(requests[1], json({{"id", requests[1]["id"]}, {"op", "control.gains"}, {"controller", "arm"},
                               {"pid", "gains/j1"}, {"i", 2.0}, {"i_clamp_max", 3.0}, {"antiwindup", false}}));
  for (const char* bad_value : {"fast", "nan", "inf"}) {
    const CliResult bad = runCli({"control", "gains", "arm", "--p", bad_value}, run_dir_.scratch());
    EXPECT_NE(bad.status, 0) << bad_value;
    EXPECT_THAT(bad.err, HasSubstr("--p")) << bad_value;
    EXPECT_EQ(lineCount(bad.err), 1) << bad.err;
  }
  EXPECT_EQ(node.requestsFor("control.gains").size(), 2u);
}

TEST_F(ControlTest, NoNodeRunningIsAClearError) {
  const CliResult result = runCli({"control", "list"}, run_dir_.scratch());
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("no servoloop node is running"));
  EXPECT_THAT(result.err, HasSubstr(run_dir_.runDir().string()));
  EXPECT_THAT(result.err, HasSubstr("servoloop launch"));
  EXPECT_EQ(lineCount(result.err), 1) << result.err;
}

TEST_F(ControlTest, UnknownNamespaceListsTheRunningNodes) {
  FakeNode node("/one_DOF_robot");
  const CliResult result = runCli({"control", "list", "-N", "/other"}, run_dir_.scratch());
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("'/other'"));
  EXPECT_THAT(result.err, HasSubstr("running nodes: /one_DOF_robot"));
  EXPECT_EQ(lineCount(result.err), 1) << result.err;
}

TEST_F(ControlTest, SeveralNodesNeedANamespace) {
  FakeNode left("/arm/left");
  FakeNode right("/arm/right");
  CliResult result = runCli({"control", "list"}, run_dir_.scratch());
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("several servoloop nodes are running (/arm/left, /arm/right)"));
  EXPECT_THAT(result.err, HasSubstr("--namespace"));
  result = runCli({"control", "load", "x", "-N", "/arm/right"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_TRUE(left.requests().empty());
  EXPECT_EQ(right.requestsFor("control.load").size(), 1u);
}

}  // namespace
}  // namespace servoloop::cli::testing
