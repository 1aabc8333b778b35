// `servoloop topic pub|echo|list|hz` against a fake node.
#include <csignal>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_client_support.hpp"
#include "wait_until.hpp"
#include "servoloop/ipc/ipc_protocol.hpp"

namespace servoloop::cli::testing {
namespace {

using ::testing::HasSubstr;
using nlohmann::json;

const char* const kCommandTopic = "/one_DOF_robot/joint1_position_controller/command";
const char* const kJointStates = "/one_DOF_robot/joint_states";

class TopicTest : public ::testing::Test {
 protected:
  ScopedRunDir run_dir_;
};

// On topic.subscribe, pushes `count` JointState messages 0.02 s of sim time
// apart (stamps 0.02, 0.04, ...) before the reply, as a node would right after.
void serveJointStates(FakeNode& node, int count) {
  node.on("topic.subscribe", [count](const json& request, servoloop::ipc::IpcConnection& connection) -> json {
    for (int i = 1; i <= count; ++i) {
      const double stamp = 0.02 * i;
      connection.send(servoloop::ipc::makeIpcStreamMessage(
          request["topic"].get<std::string>(),
          {{"type", "sensor_msgs/JointState"},
           {"stamp", stamp},
           {"msg",
            {{"stamp", stamp},
             {"name", {"joint1"}},
             {"position", {0.1 * i}},
             {"velocity", {0.5}},
             {"effort", {2.0}}}}}));
    }
    return nullptr;
  });
}

TEST_F(TopicTest, PubOnceSendsTheFullMessage) {
  FakeNode node("/one_DOF_robot");
  const CliResult result =
      runCli({"topic", "pub", kCommandTopic, "std_msgs/Float64", "1.0"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  const auto pubs = node.requestsFor("topic.pub");
  ASSERT_EQ(pubs.size(), 1u);
  EXPECT_EQ(pubs[0]["topic"], kCommandTopic);
  EXPECT_EQ(pubs[0]["type"], "std_msgs/Float64");
  EXPECT_EQ(pubs[0]["msg"], json({{"data", 1.0}}));
}

TEST_F(TopicTest, PubArraysAndYamlMessages) {
  FakeNode node("/one_DOF_robot");
  ASSERT_EQ(runCli({"topic", "pub", "/one_DOF_robot/x", "std_msgs/Float64MultiArray", "[1, 2.5]"},
                   run_dir_.scratch())
                .status,
            0);
  ASSERT_EQ(runCli({"topic", "pub", "/one_DOF_robot/js", "sensor_msgs/JointState",
                    "{name: [joint1], position: [0.5]}"},
                   run_dir_.scratch())
                .status,
            0);
  const auto pubs = node.requestsFor("topic.pub");
  ASSERT_EQ(pubs.size(), 2u);
  EXPECT_EQ(pubs[0]["msg"], json({{"data", {1.0, 2.5}}}));
  EXPECT_EQ(pubs[1]["msg"]["name"], json({"joint1"}));
  EXPECT_EQ(pubs[1]["msg"]["position"], json({0.5}));
}

TEST_F(TopicTest, BadValuesAndUnknownTypesFailBeforeAnyRequest) {
  FakeNode node("/one_DOF_robot");
  CliResult result =
      runCli({"topic", "pub", kCommandTopic, "std_msgs/Float64", "abc"}, run_dir_.scratch());
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("std_msgs/Float64"));
  EXPECT_EQ(lineCount(result.err), 1) << result.err;
  result = runCli({"topic", "pub", kCommandTopic, "std_msgs/Int32", "1"}, run_dir_.scratch());
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("unknown message type 'std_msgs/Int32'; known types:"));
  EXPECT_THAT(result.err, HasSubstr("std_msgs/Float64"));
  result = runCli({"topic", "pub", kCommandTopic}, run_dir_.scratch());
  EXPECT_NE(result.status, 0);
  EXPECT_EQ(lineCount(result.err), 1) << result.err;
  EXPECT_TRUE(node.requests().empty());
}

TEST_F(TopicTest, PubAtARateWithACountTakesAtLeastThatLong) {
  FakeNode node("/one_DOF_robot");
  const CliResult result = runCli(
      {"topic", "pub", "-r", "20", "-n", "10", kCommandTopic, "std_msgs/Float64", "1"},
      run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(node.requestsFor("topic.pub").size(), 10u);
  // Ten messages at 20 Hz span nine periods at least.
  EXPECT_GE(result.elapsed_s, 9 * 0.05 * 0.95);
}

TEST_F(TopicTest, PubAtARateRunsUntilSigint) {
  FakeNode node("/one_DOF_robot");
  CliProcess pub({"topic", "pub", "-r", "50", kCommandTopic, "std_msgs/Float64", "1"},
                 run_dir_.scratch());
  // It keeps publishing: twenty messages arrive (0.4 s at 50 Hz; the bound
  // is for a loaded machine), and it is still running when interrupted.
  ASSERT_TRUE(servoloop::testing::waitUntil([&] { return node.requestsFor("topic.pub").size() >= 20; },
                                            std::chrono::seconds(30)))
      << pub.currentErr();
  pub.signal(SIGINT);
  const CliResult result = pub.wait(10.0);
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_GE(node.requestsFor("topic.pub").size(), 20u);
}

TEST_F(TopicTest, TopicGoesToTheNodeWhoseNamespacePrefixesIt) {
  FakeNode left("/arm/left");
  FakeNode right("/arm/right");
  const CliResult result =
      runCli({"topic", "pub", "/arm/right/c/command", "std_msgs/Float64", "2"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_TRUE(left.requests().empty());
  EXPECT_EQ(right.requestsFor("topic.pub").size(), 1u);
}

TEST_F(TopicTest, EchoJsonPrintsOneObjectPerLineInTheDocumentedForm) {
  FakeNode node("/one_DOF_robot");
  serveJointStates(node, 5);
  const CliResult result =
      runCli({"topic", "echo", "-n", "2", "--json", kJointStates}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(result.out,
            "{\"stamp\": 0.02, \"name\": [\"joint1\"], \"position\": [0.1], \"velocity\": [0.5], "
            "\"effort\": [2.0]}\n"
            "{\"stamp\": 0.04, \"name\": [\"joint1\"], \"position\": [0.2], \"velocity\": [0.5], "
            "\"effort\": [2.0]}\n");
  EXPECT_EQ(node.requestsFor("topic.subscribe").at(0)["topic"], kJointStates);
}

TEST_F(TopicTest, EchoTextSeparatesMessagesWithDashes) {
  FakeNode node("/one_DOF_robot");
  node.on("topic.subscribe", [](const json& request, servoloop::ipc::IpcConnection& connection) -> json {
    for (double value : {1.0, 2.5}) {
      connection.send(servoloop::ipc::makeIpcStreamMessage(
          request["topic"].get<std::string>(),
          {{"type", "std_msgs/Float64"}, {"stamp", 0.1}, {"msg", {{"data", value}}}}));
    }
    return nullptr;
  });
  const CliResult result = runCli({"topic", "echo", "-n", "2", kCommandTopic}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(result.out, "data: 1.0\n---\ndata: 2.5\n---\n");
}

TEST_F(TopicTest, EchoOfAMissingTopicRelaysTheNodesError) {
  FakeNode node("/one_DOF_robot");
  node.on("topic.subscribe", [](const json&, auto&) -> json {
    return {{"ok", false}, {"error", "no topic '/one_DOF_robot/nope'; see `servoloop topic list`"}};
  });
  const CliResult result = runCli({"topic", "echo", "/one_DOF_robot/nope"}, run_dir_.scratch());
  EXPECT_EQ(result.status, 1);
  EXPECT_EQ(result.err,
            "servoloop topic echo: error: no topic '/one_DOF_robot/nope'; see `servoloop topic "
            "list`\n");
}

TEST_F(TopicTest, ListTextAndJson) {
  FakeNode node("/one_DOF_robot");
  const json topics = json::parse(R"([
    {"name": "/one_DOF_robot/joint_states", "type": "sensor_msgs/JointState", "publishers": 1, "subscribers": 0},
    {"name": "/one_DOF_robot/c/command", "type": "std_msgs/Float64", "publishers": 0, "subscribers": 1}
  ])");
  node.on("topic.list", [topics](const json&, auto&) -> json { return {{"topics", topics}}; });
  CliResult result = runCli({"topic", "list"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(result.out,
            "/one_DOF_robot/joint_states  sensor_msgs/JointState\n"
            "/one_DOF_robot/c/command     std_msgs/Float64\n");
  result = runCli({"topic", "list", "--json"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  json tagged = topics;
  for (auto& topic : tagged) topic["node"] = "/one_DOF_robot";
  EXPECT_EQ(json::parse(result.out), tagged);
}

// Answers topic.list with one topic per name given.
void serveTopicList(FakeNode& node, const std::vector<std::string>& names) {
  json topics = json::array();
  for (const auto& name : names) {
    topics.push_back({{"name", name}, {"type", "std_msgs/Float64"}, {"publishers", 1}, {"subscribers", 0}});
  }
  node.on("topic.list", [topics](const json&, auto&) -> json { return {{"topics", topics}}; });
}

TEST_F(TopicTest, ListWithoutNamespaceShowsTheTopicsOfEveryRunningNode) {
  FakeNode left("/arm/left");
  FakeNode right("/arm/right");
  serveTopicList(left, {"/arm/left/c/command"});
  serveTopicList(right, {"/arm/right/c/command", "/arm/right/joint_states"});
  CliResult result = runCli({"topic", "list"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(result.out,
            "/arm/left/c/command      std_msgs/Float64  node /arm/left\n"
            "/arm/right/c/command     std_msgs/Float64  node /arm/right\n"
            "/arm/right/joint_states  std_msgs/Float64  node /arm/right\n");

  result = runCli({"topic", "list", "--json"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  const json listed = json::parse(result.out);
  ASSERT_EQ(listed.size(), 3u);
  EXPECT_EQ(listed[0]["name"], "/arm/left/c/command");
  EXPECT_EQ(listed[0]["node"], "/arm/left");
  EXPECT_EQ(listed[2]["name"], "/arm/right/joint_states");
  EXPECT_EQ(listed[2]["node"], "/arm/right");

  // --namespace asks that node only.
  result = runCli({"topic", "list", "-N", "/arm/right"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(result.out,
            "/arm/right/c/command     std_msgs/Float64\n"
            "/arm/right/joint_states  std_msgs/Float64\n");
  EXPECT_EQ(left.requestsFor("topic.list").size(), 2u);  // the two runs without -N
}

TEST_F(TopicTest, ListLeavesOutAWorldSocketWithNoRobot) {
  FakeNode world("/");
  world.on("topic.list", [](const json&, auto&) -> json {
    return {{"ok", false}, {"error", "'topic.list': this world has no robot yet"}};
  });
  FakeNode robot("/one_DOF_robot");
  serveTopicList(robot, {"/one_DOF_robot/joint_states"});
  CliResult result = runCli({"topic", "list"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(result.out, "/one_DOF_robot/joint_states  std_msgs/Float64\n");
}

TEST_F(TopicTest, ListFailsWithTheNodesErrorWhenNoNodeAnswers) {
  FakeNode world("/");
  world.on("topic.list", [](const json&, auto&) -> json {
    return {{"ok", false}, {"error", "'topic.list': this world has no robot yet"}};
  });
  const CliResult result = runCli({"topic", "list"}, run_dir_.scratch());
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("this world has no robot yet"));
  EXPECT_EQ(lineCount(result.err), 1) << result.err;
}

TEST_F(TopicTest, HzReportsTheSimRateFromStamps) {
  FakeNode node("/one_DOF_robot");
  serveJointStates(node, 11);  // 10 intervals of 0.02 s
  CliResult result = runCli({"topic", "hz", "-n", "11", kJointStates}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("average rate (sim time): 50.000\n\tmin: 0.020s max: 0.020s "
                                    "std dev: 0.00000s window: 10\n"));
  EXPECT_THAT(result.out, HasSubstr("average rate (wall time): "));

  result = runCli({"topic", "hz", "--json", "-n", "6", "--window", "3", kJointStates},
                  run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  // The last report covers every message.
  std::string last_line;
  std::istringstream lines(result.out);
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty()) last_line = line;
  }
  const auto report = json::parse(last_line);
  EXPECT_EQ(report["messages"], 6);
  EXPECT_NEAR(report["sim"]["rate"].get<double>(), 50.0, 1e-9);
  EXPECT_EQ(report["sim"]["window"], 3);
}

}  // namespace
}  // namespace servoloop::cli::testing
