// The fault suite. One real node, the seed robot on the mock backend in real
// time, serving its socket on a private SERVOLOOP_RUN_DIR:
//   - killed with SIGKILL while a client streams from it, then launched again
//     over the socket and lock files it left;
//   - its clients killed at every stage of a request (command-line clients
//     and raw connections that stop mid-line, never read, or vanish);
//   - storms of concurrent controller switches and loads from several clients.
// After each, the node must answer, its controllers must be in a state the
// requests explain, its simulated time must still advance, and the file
// descriptors and threads the clients cost must be given back.
#include <signal.h>
#include <sys/socket.h>

#include <atomic>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_client_support.hpp"
#include "ipc_test_support.hpp"
#include "servoloop/ipc/ipc_socket_path.hpp"
#include "wait_until.hpp"

namespace servoloop::cli::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using servoloop::ipc::testing::RawClient;
using servoloop::testing::waitUntil;
using ::testing::HasSubstr;

const std::string kSeedLaunch =
    (fs::path(SERVOLOOP_SOURCE_DIR) / "robots" / "one_dof" / "one_dof_w_jnt_ctl.launch.yaml").string();
const char* const kNamespace = "/one_DOF_robot";
const char* const kPositionController = "joint1_position_controller";

// One request on a fresh connection and its reply; nullopt when the node does
// not answer within timeout_s.
std::optional<json> request(const json& message, double timeout_s = 10.0) {
  const auto line = servoloop::ipc::testing::requestLine(servoloop::ipc::socketPathFor(kNamespace), message.dump(),
                                                         timeout_s);
  if (!line) return std::nullopt;
  const json reply = json::parse(*line, nullptr, false);
  if (reply.is_discarded()) return std::nullopt;
  return reply;
}

std::optional<double> simTime() {
  const auto reply = request({{"id", 1}, {"op", "ping"}}, 5.0);
  if (!reply || !reply->value("ok", false)) return std::nullopt;
  return (*reply)["sim_time"].get<double>();
}

// The node answers, and its simulated time moves on between two pings.
bool nodeServesAndRuns() {
  const auto first = simTime();
  if (!first) return false;
  return waitUntil([&] { const auto now = simTime(); return now && *now > *first; }, std::chrono::seconds(10));
}

// name -> state, from control.list.
std::map<std::string, std::string> controllerStates() {
  std::map<std::string, std::string> states;
  const auto reply = request({{"id", 2}, {"op", "control.list"}});
  if (!reply || !reply->value("ok", false)) return states;
  for (const json& controller : (*reply)["controllers"]) {
    states[controller["name"].get<std::string>()] = controller["state"].get<std::string>();
  }
  return states;
}

std::size_t entriesIn(const fs::path& dir) {
  std::error_code error;
  std::size_t count = 0;
  for (fs::directory_iterator it(dir, error), end; !error && it != end; it.increment(error)) ++count;
  return count;
}

class FaultTest : public ::testing::Test {
 protected:
  void launchNode() {
    node_ = std::make_unique<CliProcess>(std::vector<std::string>{"launch", kSeedLaunch, "--backend", "mock"},
                                         run_dir_.scratch());
    ASSERT_TRUE(waitUntil([] { return simTime().has_value(); }, std::chrono::seconds(60))) << node_->currentErr();
  }

  void stopNode() {
    node_->signal(SIGINT);
    const CliResult result = node_->wait(60.0);
    EXPECT_FALSE(result.timed_out);
    EXPECT_EQ(result.status, 0) << result.err;
  }

  fs::path procDir(const char* what) const { return fs::path("/proc") / std::to_string(node_->pid()) / what; }

  ScopedRunDir run_dir_;
  std::unique_ptr<CliProcess> node_;
};

TEST_F(FaultTest, NodeKilledMidStreamIsLaunchedAgainOverWhatItLeft) {
  launchNode();
  CliProcess echo({"topic", "echo", std::string(kNamespace) + "/joint_states"}, run_dir_.scratch());
  ASSERT_TRUE(echo.waitForOutput("position", 30.0)) << echo.currentErr();

  node_->signal(SIGKILL);
  const CliResult killed = node_->wait(30.0);
  EXPECT_FALSE(killed.timed_out);
  // The streaming client ends with one error, not a hang or a crash.
  const CliResult echoed = echo.wait(30.0);
  ASSERT_FALSE(echoed.timed_out) << "topic echo did not notice the node died";
  EXPECT_NE(echoed.status, 0);
  EXPECT_NE(echoed.status, -1) << "topic echo was killed by a signal: " << echoed.err;
  EXPECT_LE(lineCount(echoed.err), 2) << echoed.err;
  EXPECT_THAT(echoed.err, HasSubstr("node"));
  // What the killed node left behind: its socket file and lock file.
  EXPECT_TRUE(fs::exists(servoloop::ipc::socketPathFor(kNamespace)));

  // The same launch starts over them, and serves with its controllers running.
  launchNode();
  EXPECT_TRUE(nodeServesAndRuns());
  const auto states = controllerStates();
  EXPECT_EQ(states.at(kPositionController), "running");
  EXPECT_EQ(states.at("joint_state_controller"), "running");
  stopNode();
}

TEST_F(FaultTest, ClientsKilledAtEveryStageLeaveTheNodeServingAndGiveBackTheirResources) {
  launchNode();
  ASSERT_TRUE(nodeServesAndRuns());
  const std::size_t fds_before = entriesIn(procDir("fd"));
  const std::size_t threads_before = entriesIn(procDir("task"));

  const std::string command_topic = std::string(kNamespace) + "/" + kPositionController + "/command";
  const std::vector<std::vector<std::string>> commands = {
      {"topic", "echo", std::string(kNamespace) + "/joint_states"},
      {"topic", "pub", "-r", "100", command_topic, "std_msgs/Float64", "0.5"},
      {"control", "list"},
      {"control", "switch", "--start", kPositionController},
      {"param", "dump"},
      {"spawner", "--timeout", "5", "joint_state_controller"},
  };
  // Killed as soon as they start, and killed once they have printed.
  for (int round = 0; round < 3; ++round) {
    for (const auto& command : commands) {
      CliProcess early(command, run_dir_.scratch());
      early.signal(SIGKILL);
      early.wait(30.0);
      CliProcess late(command, run_dir_.scratch());
      waitUntil([&] { return !late.currentOut().empty() || !late.currentErr().empty(); }, std::chrono::seconds(5));
      late.signal(SIGKILL);
      late.wait(30.0);
    }
  }
  // Raw clients: a request cut mid-line, requests never read, a subscription
  // dropped without a word, a half-closed switch.
  for (int i = 0; i < 20; ++i) {
    {
      RawClient cut(servoloop::ipc::socketPathFor(kNamespace));
      cut.sendBytes(R"({"id": 1, "op": "control.sw)");
    }
    {
      RawClient deaf(servoloop::ipc::socketPathFor(kNamespace));
      std::string many;
      for (int k = 0; k < 200; ++k) many += R"({"id": 2, "op": "param.dump"})" "\n";
      deaf.sendBytes(many);
    }
    {
      RawClient gone(servoloop::ipc::socketPathFor(kNamespace));
      gone.sendBytes(json({{"id", 3}, {"op", "topic.subscribe"}, {"topic", std::string(kNamespace) + "/joint_states"}})
                         .dump() +
                     "\n");
      gone.readLine(5.0);
    }
  }

  // The node serves, its controllers are as they were (no request above
  // stops one), and what the clients held is given back.
  EXPECT_TRUE(nodeServesAndRuns());
  const auto states = controllerStates();
  EXPECT_EQ(states.at(kPositionController), "running");
  EXPECT_EQ(states.at("joint_state_controller"), "running");
  EXPECT_TRUE(waitUntil([&] { return entriesIn(procDir("fd")) <= fds_before; }, std::chrono::seconds(30)))
      << entriesIn(procDir("fd")) << " open files against " << fds_before << " before the clients";
  EXPECT_TRUE(waitUntil([&] { return entriesIn(procDir("task")) <= threads_before; }, std::chrono::seconds(30)))
      << entriesIn(procDir("task")) << " threads against " << threads_before << " before the clients";
  stopNode();
}

// A switch whose client shut down its sending side still runs and is still
// answered (the reply used to be lost when the connection closed at EOF).
TEST_F(FaultTest, HalfClosedSwitchRunsAndIsAnswered) {
  launchNode();
  RawClient client(servoloop::ipc::socketPathFor(kNamespace));
  ASSERT_TRUE(client.sendBytes(json({{"id", 7}, {"op", "control.switch"}, {"stop", {kPositionController}}}).dump() +
                               "\n"));
  ::shutdown(client.fd(), SHUT_WR);
  const auto line = client.readLine(30.0);
  ASSERT_TRUE(line.has_value()) << "the switch's reply was lost";
  const json reply = json::parse(*line);
  EXPECT_EQ(reply["id"], 7);
  EXPECT_EQ(reply["ok"], true) << reply.dump();
  EXPECT_EQ(controllerStates().at(kPositionController), "stopped");
  stopNode();
}

// Four clients switch the position controller off and on, two load and
// unload a spare controller, all at once. Every request gets exactly one
// reply (ok, or an error that says why), the loop keeps running, and a last
// switch finds the manager in a consistent state.
TEST_F(FaultTest, SwitchAndLoadStormsFromConcurrentClients) {
  launchNode();
  const auto spare = request({{"id", 1},
                              {"op", "param.set"},
                              {"name", std::string(kNamespace) + "/spare_controller"},
                              {"value", {{"type", "joint_state_controller/JointStateController"},
                                         {"publish_rate", 10}}}});
  ASSERT_TRUE(spare && spare->value("ok", false)) << (spare ? spare->dump() : "no reply");

  constexpr int kRequestsPerClient = 60;
  std::atomic<int> replies{0};
  std::atomic<int> missing{0};
  std::atomic<int> malformed{0};
  const auto client = [&](int which) {
    RawClient connection(servoloop::ipc::socketPathFor(kNamespace));
    for (int i = 0; i < kRequestsPerClient; ++i) {
      json message{{"id", i}};
      if (which < 4) {
        message["op"] = "control.switch";
        message[i % 2 == 0 ? "stop" : "start"] = json::array({kPositionController});
        message["strictness"] = "best_effort";
      } else {
        message["op"] = i % 2 == 0 ? "control.load" : "control.unload";
        message["name"] = "spare_controller";
      }
      if (!connection.sendBytes(message.dump() + "\n", 30.0)) {
        ++missing;
        return;
      }
      const auto line = connection.readLine(60.0);
      if (!line) {
        ++missing;
        return;
      }
      const json reply = json::parse(*line, nullptr, false);
      const bool well_formed = reply.is_object() && reply.value("id", -1) == i && reply.contains("ok") &&
                               (reply["ok"] == true || !reply.value("error", std::string()).empty());
      if (!well_formed) ++malformed;
      ++replies;
    }
  };
  std::vector<std::thread> clients;
  for (int which = 0; which < 6; ++which) clients.emplace_back(client, which);
  for (auto& thread : clients) thread.join();

  EXPECT_EQ(missing.load(), 0);
  EXPECT_EQ(malformed.load(), 0);
  EXPECT_EQ(replies.load(), 6 * kRequestsPerClient);
  EXPECT_TRUE(nodeServesAndRuns());

  // The last word: start the position controller, unload the spare if loaded.
  const auto start = request({{"id", 9}, {"op", "control.switch"}, {"start", {kPositionController}},
                              {"strictness", "best_effort"}});
  ASSERT_TRUE(start && start->value("ok", false)) << (start ? start->dump() : "no reply");
  auto states = controllerStates();
  EXPECT_EQ(states.at(kPositionController), "running");
  EXPECT_EQ(states.at("joint_state_controller"), "running");
  if (states.count("spare_controller")) {
    EXPECT_NE(states.at("spare_controller"), "running");
    const auto unload = request({{"id", 10}, {"op", "control.unload"}, {"name", "spare_controller"}});
    EXPECT_TRUE(unload && unload->value("ok", false)) << (unload ? unload->dump() : "no reply");
  }
  stopNode();
}

}  // namespace
}  // namespace servoloop::cli::testing
