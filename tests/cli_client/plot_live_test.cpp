// `servoloop plot --topic` against a fake node: it subscribes, writes what
// the node streams as CSV rows (the format of `launch --record`), stops after
// -n messages or --duration, and draws the PNG.
#include <filesystem>
#include <string>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_client_support.hpp"
#include "servoloop/ipc/ipc_protocol.hpp"

namespace servoloop::cli::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using nlohmann::json;

const char* const kJointStates = "/one_DOF_robot/joint_states";
const char* const kCommand = "/one_DOF_robot/joint1_position_controller/command";
const std::string kPngSignature("\x89PNG\r\n\x1a\n", 8);

// On topic.subscribe of the joint states, streams `count` JointState messages
// stamped 0.02 k (k = 0, 1, ...); of the command, one Float64 at 0.
void serveTopics(FakeNode& node, int count) {
  node.on("topic.subscribe", [count](const json& request, servoloop::ipc::IpcConnection& connection) -> json {
    const std::string topic = request["topic"].get<std::string>();
    if (topic == kCommand) {
      connection.send(servoloop::ipc::makeIpcStreamMessage(
          topic, {{"type", "std_msgs/Float64"}, {"stamp", 0.0}, {"msg", {{"data", 1.0}}}}));
      return nullptr;
    }
    if (topic != kJointStates) return {{"ok", false}, {"error", "no topic '" + topic + "'"}};
    for (int k = 0; k < count; ++k) {
      const double stamp = 0.02 * k;
      connection.send(servoloop::ipc::makeIpcStreamMessage(
          topic, {{"type", "sensor_msgs/JointState"},
                  {"stamp", stamp},
                  {"msg",
                   {{"stamp", stamp},
                    {"name", {"joint1"}},
                    {"position", {0.25 * k}},
                    {"velocity", {0.5}},
                    {"effort", {2.0}}}}}));
    }
    return nullptr;
  });
}

class PlotLiveTest : public ::testing::Test {
 protected:
  ScopedRunDir run_dir_;
};

TEST_F(PlotLiveTest, CountStopsAfterThatManyMessagesAndThePlotIsDrawn) {
  FakeNode node("/one_DOF_robot");
  serveTopics(node, 10);
  const fs::path png = run_dir_.scratch() / "live.png";
  const fs::path csv_dir = run_dir_.scratch() / "csv";
  const CliResult result = runCli({"plot", "--topic", kJointStates, "--topic", kCommand, "-n", "4", "-o",
                                   png.string(), "--save-csv", csv_dir.string()},
                                  run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(result.out, png.string() + "\n");
  EXPECT_EQ(readFile(png).substr(0, 8), kPngSignature);

  // Exactly 4 joint states, in the recorder's CSV format, stamps as given.
  EXPECT_EQ(readFile(csv_dir / "one_DOF_robot_joint_states.csv"),
            "time,joint1.position,joint1.velocity,joint1.effort\n"
            "0.0,0.0,0.5,2.0\n"
            "0.02,0.25,0.5,2.0\n"
            "0.04,0.5,0.5,2.0\n"
            "0.06,0.75,0.5,2.0\n");
  EXPECT_EQ(readFile(csv_dir / "one_DOF_robot_joint1_position_controller_command.csv"), "time,data\n0.0,1.0\n");

  const auto subscribes = node.requestsFor("topic.subscribe");
  ASSERT_EQ(subscribes.size(), 2u);
  EXPECT_EQ(subscribes[0]["topic"], kJointStates);
  EXPECT_EQ(subscribes[1]["topic"], kCommand);
}

TEST_F(PlotLiveTest, DurationIsWallTime) {
  FakeNode node("/one_DOF_robot");
  serveTopics(node, 3);
  const fs::path png = run_dir_.scratch() / "live.png";
  const CliResult result =
      runCli({"plot", "--topic", kJointStates, "--duration", "0.5", "-o", png.string()}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_GE(result.elapsed_s, 0.5);
  EXPECT_EQ(readFile(png).substr(0, 8), kPngSignature);
}

TEST_F(PlotLiveTest, ATopicWithoutMessagesIsAnError) {
  FakeNode node("/one_DOF_robot");
  serveTopics(node, 0);
  const CliResult result = runCli(
      {"plot", "--topic", kJointStates, "--duration", "0.3", "-o", (run_dir_.scratch() / "x.png").string()},
      run_dir_.scratch());
  EXPECT_EQ(result.status, 1);
  EXPECT_EQ(lineCount(result.err), 1) << result.err;
  EXPECT_THAT(result.err, HasSubstr("no message arrived on /one_DOF_robot/joint_states within 0.3 s"));
}

TEST_F(PlotLiveTest, AnUnknownTopicRelaysTheNodesError) {
  FakeNode node("/one_DOF_robot");
  serveTopics(node, 1);
  const CliResult result =
      runCli({"plot", "--topic", "/one_DOF_robot/nope", "-n", "1", "-o", "x.png"}, run_dir_.scratch());
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("no topic '/one_DOF_robot/nope'"));
}

TEST_F(PlotLiveTest, CsvFilesAndTopicsDoNotMix) {
  const CliResult result = runCli({"plot", "-o", "x.png"}, run_dir_.scratch());
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("--topic"));
  EXPECT_EQ(lineCount(result.err), 1) << result.err;
}

}  // namespace
}  // namespace servoloop::cli::testing
