// IpcClient: the errors a command-line user sees, timeouts, waiting for a
// node to come up, stale sockets, and round-trip latency.
#include <algorithm>
#include <chrono>
#include <fstream>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <sys/socket.h>

#include "ipc_fixture.hpp"
#include "servoloop/ipc/ipc_client.hpp"

namespace servoloop::ipc {
namespace {

using testing::IpcServerFixture;
using testing::kTestNode;
using testing::ScopedRunDir;
using IpcClientTest = IpcServerFixture;
using Clock = std::chrono::steady_clock;

IpcServer::Handler echoHandler() {
  return [](const nlohmann::json& request, IpcConnection&) {
    return nlohmann::json{{"value", request.value("value", nlohmann::json())}};
  };
}

std::string connectError(std::string_view node_name) {
  try {
    IpcClient::connectToNode(node_name);
  } catch (const Error& error) {
    return error.what();
  }
  return "<connected>";
}

// A socket file nobody listens on, as a crashed node leaves behind.
void makeStaleSocket(const std::filesystem::path& path) {
  ensurePrivateDirectory(path.parent_path());
  IpcFd fd(::socket(AF_UNIX, SOCK_STREAM, 0));
  const sockaddr_un address = makeUnixAddress(path);
  ASSERT_EQ(::bind(fd.get(), reinterpret_cast<const sockaddr*>(&address), sizeof(address)), 0);
}

TEST(IpcClient, NoNodeRunningMessageTellsHowToStartOne) {
  ScopedRunDir dir;
  const std::string expected = "no servoloop node is running for namespace '/one_DOF_robot' (looked for " +
                               (dir.runDir() / "one_DOF_robot.sock").native() +
                               "); start one with `servoloop launch <launch file>`";
  EXPECT_EQ(connectError("/one_DOF_robot"), expected) << "run directory missing";

  ensurePrivateDirectory(dir.runDir());
  EXPECT_EQ(connectError("/one_DOF_robot"), expected) << "run directory empty";

  makeStaleSocket(dir.runDir() / "one_DOF_robot.sock");
  EXPECT_EQ(connectError("/one_DOF_robot"), expected) << "stale socket file";
}

TEST(IpcClient, StaleSocketIsReplacedByANewServer) {
  ScopedRunDir dir;
  const std::filesystem::path path = socketPathFor(kTestNode);
  makeStaleSocket(path);
  ASSERT_TRUE(std::filesystem::is_socket(path));

  IpcServer server(path, echoHandler());
  server.start();
  IpcClient client = IpcClient::connectToNode(kTestNode);
  EXPECT_EQ(client.call("echo", {{"value", "fresh"}})["value"], "fresh");
  EXPECT_EQ(client.nodeName(), "/one_DOF_robot");
}

TEST(IpcClient, ServerRefusesToReplaceANonSocketFile) {
  ScopedRunDir dir;
  const std::filesystem::path path = socketPathFor(kTestNode);
  ensurePrivateDirectory(dir.runDir());
  std::ofstream(path) << "important data";
  IpcServer server(path, echoHandler());
  try {
    server.start();
    ADD_FAILURE() << "a regular file must not be replaced";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("exists and is not a socket"), std::string::npos);
  }
  EXPECT_TRUE(std::filesystem::is_regular_file(path));
}

TEST_F(IpcClientTest, TimedOutRequestThrowsAndItsLateReplyIsDiscarded) {
  IpcClient client = IpcClient::connectToNode(kTestNode);
  const auto start = Clock::now();
  try {
    client.request({{"op", "slow"}, {"ms", 300}}, 0.05);
    ADD_FAILURE() << "must time out";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()),
              "the servoloop node for namespace '/one_DOF_robot' did not answer 'slow' within 0.05 s (" +
                  server_->socketPath().native() + ")");
  }
  EXPECT_LT(Clock::now() - start, std::chrono::seconds(2)) << "must give up at its timeout, not wait on";
  // The next request gets its own reply, not the late one for "slow".
  const nlohmann::json reply = client.request({{"op", "echo"}, {"value", "next"}}, 5.0);
  EXPECT_EQ(reply["value"], "next");
  EXPECT_EQ(reply["id"], 2);
}

TEST_F(IpcClientTest, RequestValidationAndOversizeAreCaughtBeforeSending) {
  IpcClient client = IpcClient::connectToNode(kTestNode);
  EXPECT_THROW(client.request(nlohmann::json::array()), Error);
  EXPECT_THROW(client.request({{"value", 1}}), Error);
  try {
    client.call("echo", {{"value", std::string(kIpcMaxRequestLineBytes, 'v')}});
    ADD_FAILURE() << "an over-limit request must be refused";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("over the node's limit"), std::string::npos);
  }
  EXPECT_EQ(client.call("echo", {{"value", 1}})["value"], 1);

  IpcClient unconnected;
  EXPECT_THROW(unconnected.call("echo"), Error);
}

TEST(IpcClient, WaitForNodeReturnsOnceTheNodeAccepts) {
  ScopedRunDir dir;
  auto start = Clock::now();
  EXPECT_FALSE(waitForNode(kTestNode, 0.2));
  EXPECT_GE(Clock::now() - start, std::chrono::milliseconds(200));

  IpcServer server(socketPathFor(kTestNode), echoHandler());
  std::thread late_start([&server] {
    std::this_thread::sleep_for(std::chrono::milliseconds(150));
    server.start();
  });
  start = Clock::now();
  EXPECT_TRUE(waitForNode(kTestNode, 0.0)) << "0 waits forever";
  const auto waited = Clock::now() - start;
  late_start.join();
  EXPECT_GE(waited, std::chrono::milliseconds(100));
  EXPECT_LT(waited, std::chrono::seconds(3));
  EXPECT_TRUE(waitForNode(kTestNode, 1.0));
}

TEST_F(IpcClientTest, LatencyOfOneThousandRoundTrips) {
  IpcClient client = IpcClient::connectToNode(kTestNode);
  constexpr int kRoundTrips = 1000;
  std::vector<double> latencies_us;
  latencies_us.reserve(kRoundTrips);
  for (int i = 0; i < kRoundTrips; ++i) {
    const auto start = Clock::now();
    const nlohmann::json reply = client.request({{"op", "echo"}, {"value", i}});
    latencies_us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count());
    ASSERT_EQ(reply["value"], i);
  }
  std::sort(latencies_us.begin(), latencies_us.end());
  double total_us = 0.0;
  for (double latency : latencies_us) total_us += latency;
  const double mean_us = total_us / kRoundTrips;
  std::cout << "[ipc latency] " << kRoundTrips << " round trips: mean " << mean_us << " us, median "
            << latencies_us[kRoundTrips / 2] << " us, p99 " << latencies_us[kRoundTrips * 99 / 100]
            << " us, max " << latencies_us.back() << " us\n";
  RecordProperty("mean_round_trip_us", std::to_string(mean_us));
}

}  // namespace
}  // namespace servoloop::ipc
