// IpcServer robustness: concurrent clients, misbehaving clients, bad input,
// throwing handlers, pushed streams. Every case uses a real Unix socket.
#include <csignal>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "ipc_fixture.hpp"
#include "servoloop/ipc/ipc_client.hpp"

namespace servoloop::ipc {
namespace {

using testing::eventually;
using testing::IpcServerFixture;
using testing::kTestNode;
using testing::RawClient;
using IpcServerTest = IpcServerFixture;

nlohmann::json parseLine(const std::optional<std::string>& line) {
  EXPECT_TRUE(line.has_value()) << "no line from the server";
  return line ? nlohmann::json::parse(*line) : nlohmann::json();
}

// Proves the server still answers: a fresh client's echo round trip.
// The server still answers a new client. The deadline only tells a stalled
// server from a slow machine (sanitizer builds, loaded CI); it is no timing claim.
void expectServerAnswers() {
  IpcClient client = IpcClient::connectToNode(kTestNode);
  EXPECT_EQ(client.call("echo", {{"value", "still here"}}, 30.0)["value"], "still here");
}

TEST_F(IpcServerTest, RepliesCarryTheRequestIdAndResults) {
  RawClient raw(server_->socketPath());
  ASSERT_TRUE(raw.sendBytes("{\"id\": 41, \"op\": \"echo\", \"value\": [1, 2.5, \"three\"]}\n"));
  const nlohmann::json reply = parseLine(raw.readLine());
  EXPECT_EQ(reply, (nlohmann::json{{"id", 41}, {"ok", true}, {"value", {1, 2.5, "three"}}}));

  // Two requests in one write, CRLF line ends: both answered, in order.
  ASSERT_TRUE(raw.sendBytes("{\"id\":1,\"op\":\"echo\",\"value\":1}\r\n{\"id\":2,\"op\":\"list\"}\n"));
  EXPECT_EQ(parseLine(raw.readLine()), (nlohmann::json{{"id", 1}, {"ok", true}, {"value", 1}}));
  EXPECT_EQ(parseLine(raw.readLine()), (nlohmann::json{{"id", 2}, {"ok", true}, {"result", {1, 2, 3}}}));
}

TEST_F(IpcServerTest, SixteenConcurrentClientsAllAnsweredCorrectly) {
  constexpr int kClients = 16;
  constexpr int kRequestsEach = 100;
  std::atomic<int> correct{0};
  std::vector<std::thread> clients;
  for (int c = 0; c < kClients; ++c) {
    clients.emplace_back([c, &correct] {
      IpcClient client = IpcClient::connectToNode(kTestNode);
      for (int r = 0; r < kRequestsEach; ++r) {
        const std::string value = "client " + std::to_string(c) + " request " + std::to_string(r);
        const nlohmann::json reply = client.request({{"op", "echo"}, {"value", value}}, 10.0);
        if (reply["ok"] == true && reply["value"] == value) ++correct;
      }
    });
  }
  for (auto& thread : clients) thread.join();
  EXPECT_EQ(correct.load(), kClients * kRequestsEach);
  EXPECT_EQ(server_->stats().requests_handled, static_cast<std::uint64_t>(kClients * kRequestsEach));
  EXPECT_TRUE(eventually([&] { return server_->connectionCount() == 0; }));
}

TEST_F(IpcServerTest, GarbageLineGetsAnErrorAndTheConnectionStays) {
  RawClient raw(server_->socketPath());
  ASSERT_TRUE(raw.sendBytes("hello node\n"));
  const nlohmann::json reply = parseLine(raw.readLine());
  EXPECT_TRUE(reply["id"].is_null());
  EXPECT_EQ(reply["ok"], false);
  const std::string error = reply["error"];
  EXPECT_NE(error.find("request is not valid JSON"), std::string::npos) << error;
  EXPECT_NE(error.find("column"), std::string::npos) << "should say where parsing failed: " << error;

  ASSERT_TRUE(raw.sendBytes("{\"id\": 5, \"op\": \"echo\", \"value\": \"after garbage\"}\n"));
  EXPECT_EQ(parseLine(raw.readLine())["value"], "after garbage");
  EXPECT_EQ(handler_calls_.load(), 1);
}

// A number no double holds, and nesting deep enough to exhaust a recursive
// reader, are errors like any other bad line; the server answers on.
TEST_F(IpcServerTest, HugeNumbersAndDeepNestingGetAnError) {
  RawClient raw(server_->socketPath());
  ASSERT_TRUE(raw.sendBytes("{\"id\": 1e400, \"op\": \"echo\"}\n"));
  nlohmann::json reply = parseLine(raw.readLine());
  EXPECT_EQ(reply["ok"], false);
  EXPECT_NE(reply["error"].get<std::string>().find("request is not valid JSON: number overflow parsing '1e400'"),
            std::string::npos)
      << reply["error"];

  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  ASSERT_TRUE(raw.sendBytes(deep + "\n"));
  reply = parseLine(raw.readLine());
  EXPECT_EQ(reply["ok"], false);
  EXPECT_NE(reply["error"].get<std::string>().find("nests arrays/objects 100000 deep; the limit is 64"),
            std::string::npos)
      << reply["error"];

  // Brackets inside strings are text, not nesting.
  const std::string text(200, '[');
  ASSERT_TRUE(raw.sendBytes("{\"id\": 7, \"op\": \"echo\", \"value\": \"" + text + "\"}\n"));
  reply = parseLine(raw.readLine());
  EXPECT_EQ(reply["ok"], true) << reply;
  EXPECT_EQ(reply["value"], text);
  EXPECT_EQ(server_->stats().requests_rejected, 2u);
}

TEST_F(IpcServerTest, NonObjectOrMissingOpGetsAnError) {
  RawClient raw(server_->socketPath());
  struct Case {
    const char* line;
    nlohmann::json expected_id;
    const char* error_part;
  };
  const Case cases[] = {
      {"[1, 2]", nullptr, "must be a JSON object like {\"id\": 1, \"op\": \"...\"}, got an array"},
      {"42", nullptr, "got an integer"},
      {"{\"id\": 3}", 3, "no \"op\" field"},
      {"{\"id\": 4, \"op\": 5}", 4, "\"op\" must be a string, got an integer"},
      {"{\"id\": \"x\", \"op\": \"echo\"}", "x", "\"id\" must be an integer, got a string"},
  };
  for (const Case& c : cases) {
    ASSERT_TRUE(raw.sendBytes(std::string(c.line) + "\n"));
    const nlohmann::json reply = parseLine(raw.readLine());
    EXPECT_EQ(reply["id"], c.expected_id) << c.line;
    EXPECT_EQ(reply["ok"], false) << c.line;
    EXPECT_NE(reply["error"].get<std::string>().find(c.error_part), std::string::npos)
        << c.line << " -> " << reply["error"];
  }
  EXPECT_EQ(handler_calls_.load(), 0);
  EXPECT_EQ(server_->stats().requests_rejected, 5u);
  ASSERT_TRUE(raw.sendBytes("{\"id\": 6, \"op\": \"echo\"}\n"));
  EXPECT_EQ(parseLine(raw.readLine())["ok"], true);
}

TEST_F(IpcServerTest, TruncatedRequestIsDroppedSilently) {
  {
    RawClient raw(server_->socketPath());
    ASSERT_TRUE(raw.sendBytes("{\"id\": 1, \"op\": \"ec"));
    raw.close();
  }
  ASSERT_TRUE(eventually([&] { return server_->connectionCount() == 0; }));
  EXPECT_EQ(handler_calls_.load(), 0);
  EXPECT_EQ(server_->stats().requests_rejected, 0u);
  expectServerAnswers();
}

TEST_F(IpcServerTest, RequestsBeforeHalfCloseAreStillAnswered) {
  RawClient raw(server_->socketPath());
  ASSERT_TRUE(raw.sendBytes("{\"id\": 9, \"op\": \"echo\", \"value\": \"last words\"}\n{\"id\": 10, \"op\""));
  ::shutdown(raw.fd(), SHUT_WR);
  EXPECT_EQ(parseLine(raw.readLine())["value"], "last words");
  EXPECT_TRUE(raw.waitForClose()) << "the cut-off second request gets no reply; the server closes";
  EXPECT_EQ(handler_calls_.load(), 1);
}

// The request ran, so its reply must arrive even though the client shut down
// its sending side before the handler's worker answered (30 ms later), and
// the connection then closes without waiting for the grace period.
TEST_F(IpcServerTest, DeferredReplyAfterHalfCloseIsStillWritten) {
  RawClient raw(server_->socketPath());
  ASSERT_TRUE(raw.sendBytes("{\"id\": 11, \"op\": \"defer\"}\n"));
  ::shutdown(raw.fd(), SHUT_WR);
  const nlohmann::json reply = parseLine(raw.readLine());
  EXPECT_EQ(reply["id"], 11);
  EXPECT_EQ(reply["deferred"], true);
  EXPECT_TRUE(raw.waitForClose());
  EXPECT_TRUE(eventually([&] { return server_->connectionCount() == 0; }));
}

TEST_F(IpcServerTest, LineOfExactlyOneMebibyteIsAccepted) {
  nlohmann::json request{{"id", 1}, {"op", "echo"}, {"value", ""}};
  const std::size_t overhead = request.dump().size();
  request["value"] = std::string(kIpcMaxRequestLineBytes - overhead, 'v');
  const std::string line = request.dump();
  ASSERT_EQ(line.size(), kIpcMaxRequestLineBytes);

  RawClient raw(server_->socketPath());
  ASSERT_TRUE(raw.sendBytes(line + "\n"));
  const nlohmann::json reply = parseLine(raw.readLine());
  EXPECT_EQ(reply["ok"], true);
  EXPECT_EQ(reply["value"].get<std::string>().size(), kIpcMaxRequestLineBytes - overhead);
}

TEST_F(IpcServerTest, OversizedLineGetsAnErrorThenTheConnectionCloses) {
  RawClient raw(server_->socketPath());
  // One byte over the limit, then the newline. The server may close before it
  // has read all of it, so the write is allowed to fail part-way.
  raw.sendBytes(std::string(kIpcMaxRequestLineBytes + 1, 'x') + "\n", 2.0);
  const nlohmann::json reply = parseLine(raw.readLine());
  EXPECT_TRUE(reply["id"].is_null());
  EXPECT_EQ(reply["ok"], false);
  EXPECT_NE(reply["error"].get<std::string>().find("longer than 1048576 bytes (1 MiB)"), std::string::npos)
      << reply["error"];
  EXPECT_TRUE(raw.waitForClose());
  EXPECT_EQ(handler_calls_.load(), 0);
  EXPECT_EQ(server_->stats().clients_dropped_oversized, 1u);
  expectServerAnswers();
}

TEST_F(IpcServerTest, NoNewlineWithinOneMebibyteGetsAnErrorThenTheConnectionCloses) {
  RawClient raw(server_->socketPath());
  // 1.5 MiB and no newline ever: a client that does not speak this protocol.
  raw.sendBytes(std::string(kIpcMaxRequestLineBytes + kIpcMaxRequestLineBytes / 2, '{'), 2.0);
  const nlohmann::json reply = parseLine(raw.readLine());
  EXPECT_EQ(reply["ok"], false);
  EXPECT_NE(reply["error"].get<std::string>().find("missing its newline"), std::string::npos);
  EXPECT_TRUE(raw.waitForClose());
  expectServerAnswers();
}

TEST_F(IpcServerTest, ThrowingHandlerGivesErrorReplyAndServerRunsOn) {
  IpcClient client = IpcClient::connectToNode(kTestNode);
  const nlohmann::json reply =
      client.request({{"op", "throw"}, {"message", "controller 'arm_ctrl' is not loaded"}});
  EXPECT_EQ(reply["ok"], false);
  EXPECT_EQ(reply["error"], "controller 'arm_ctrl' is not loaded");

  const nlohmann::json odd = client.request({{"op", "throw_non_standard"}});
  EXPECT_EQ(odd["error"], "request 'throw_non_standard' failed with a non-standard exception");

  try {
    client.call("throw", {{"message", "line one\nline two"}});
    ADD_FAILURE() << "call() must throw on \"ok\": false";
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(), "line one line two") << "errors stay on one line";
  }
  EXPECT_EQ(client.call("echo", {{"value", 7}})["value"], 7);
}

TEST_F(IpcServerTest, HandlerReplyShapes) {
  IpcClient client = IpcClient::connectToNode(kTestNode);
  const nlohmann::json quiet = client.request({{"op", "fail_quietly"}});
  EXPECT_EQ(quiet["ok"], false);
  EXPECT_EQ(quiet["error"], "request 'fail_quietly' failed");
  EXPECT_EQ(quiet["id"], 1);

  const nlohmann::json deferred = client.request({{"op", "defer"}});
  EXPECT_EQ(deferred["ok"], true);
  EXPECT_EQ(deferred["deferred"], true);
  EXPECT_EQ(deferred["id"], 2);
}

TEST_F(IpcServerTest, ClientVanishingMidRequestDoesNotKillTheProcess) {
  // Restore the default SIGPIPE action, which terminates the process, so a
  // write without MSG_NOSIGNAL would end this test binary.
  auto* previous = std::signal(SIGPIPE, SIG_DFL);
  for (int i = 0; i < 5; ++i) {
    RawClient raw(server_->socketPath());
    ASSERT_TRUE(raw.sendBytes("{\"id\": 1, \"op\": \"slow\", \"ms\": 20}\n"
                              "{\"id\": 2, \"op\": \"big\", \"bytes\": 500000}\n"));
    raw.close();  // gone before the replies are written
  }
  EXPECT_TRUE(eventually([&] { return server_->connectionCount() == 0; }));
  expectServerAnswers();
  std::signal(SIGPIPE, previous);
}

TEST_F(IpcServerTest, ClientThatNeverReadsIsDroppedWhileOthersAreServed) {
  RawClient hog(server_->socketPath());
  ASSERT_TRUE(hog.sendBytes("{\"id\": 0, \"op\": \"subscribe\"}\n"));
  ASSERT_TRUE(eventually([&] { return subscribers().size() == 1; }));

  // 64 KiB replies the hog never reads: 12 MiB in all, over the 8 MiB bound
  // plus what the socket buffers hold.
  std::string requests;
  for (int i = 1; i <= 200; ++i) {
    requests += "{\"id\": " + std::to_string(i) + ", \"op\": \"big\", \"bytes\": 65536}\n";
  }
  ASSERT_TRUE(hog.sendBytes(requests));

  // Meanwhile another client is still answered: the hog cannot stall the server.
  expectServerAnswers();

  EXPECT_TRUE(eventually([&] { return server_->stats().clients_dropped_slow == 1; }));
  EXPECT_TRUE(eventually([&] { return unsubscribed_.load() == 1; })) << "onClose must run on a drop";
  EXPECT_TRUE(subscribers().empty());
  EXPECT_TRUE(hog.waitForClose(10.0));
  expectServerAnswers();
}

TEST_F(IpcServerTest, StreamMessagesPushedFromAnotherThread) {
  IpcClient client = IpcClient::connectToNode(kTestNode);
  client.call("subscribe");
  ASSERT_EQ(subscribers().size(), 1u);

  constexpr int kMessages = 200;
  std::thread delivery([this] {
    const auto connection = subscribers().front();
    for (int i = 0; i < kMessages; ++i) {
      connection->send(makeIpcStreamMessage("/one_DOF_robot/joint_states", {{"seq", i}}));
    }
  });
  // A request in the middle: stream messages that arrive first are kept.
  EXPECT_EQ(client.call("echo", {{"value", "mid-stream"}})["value"], "mid-stream");
  delivery.join();

  for (int i = 0; i < kMessages; ++i) {
    const std::optional<nlohmann::json> message = client.readStream(2.0);
    ASSERT_TRUE(message.has_value()) << "message " << i;
    EXPECT_EQ((*message)["stream"], "/one_DOF_robot/joint_states");
    EXPECT_EQ((*message)["seq"], i);
  }
  EXPECT_FALSE(client.readStream(0.05).has_value());

  const auto connection = subscribers().front();
  client.close();
  EXPECT_TRUE(eventually([&] { return unsubscribed_.load() == 1; }));
  EXPECT_FALSE(connection->isOpen());
  EXPECT_FALSE(connection->send(makeIpcStreamMessage("late")));
  bool ran = false;
  connection->onClose([&ran] { ran = true; });
  EXPECT_TRUE(ran) << "onClose on a closed connection runs at once";
}

TEST_F(IpcServerTest, StopClosesClientsAndRemovesTheSocket) {
  IpcClient client = IpcClient::connectToNode(kTestNode);
  client.call("subscribe");
  server_->stop();
  EXPECT_EQ(unsubscribed_.load(), 1);
  EXPECT_FALSE(std::filesystem::exists(server_->socketPath()));
  try {
    client.call("echo", {}, 2.0);
    ADD_FAILURE() << "a request to a stopped node must throw";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("closed the connection"), std::string::npos) << error.what();
  }
  server_->start();  // a stopped server starts again on the same path
  expectServerAnswers();
}

TEST_F(IpcServerTest, SecondServerForTheSameNamespaceIsRefused) {
  IpcServer second(socketPathFor(kTestNode), [](const nlohmann::json&, IpcConnection&) {
    return nlohmann::json();
  });
  try {
    second.start();
    ADD_FAILURE() << "two nodes must not share a socket";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("already running for namespace '/one_DOF_robot'"),
              std::string::npos)
        << error.what();
  }
  expectServerAnswers();
}

}  // namespace
}  // namespace servoloop::ipc
