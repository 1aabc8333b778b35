// The view from the command line, as users run it: `servoloop launch FILE
// --view [HOST:]PORT [--view-control]` and `servoloop view [HOST:]PORT`
// attaching to a world running in another process; a port in use, a
// non-loopback address and --view-control without a view.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <regex>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "temp_dir.hpp"
#include "wait_until.hpp"
#include "ws_test_client.hpp"

namespace {

using nlohmann::json;
using servoloop::testing::ChildProcess;
using servoloop::testing::ProcessOptions;
using servoloop::testing::nextOfType;
using servoloop::testing::TempDir;

constexpr std::chrono::seconds kMessageWait{30};

const std::string kSeedLaunch = std::string(SERVOLOOP_SOURCE_DIR) + "/robots/one_dof/one_dof_w_jnt_ctl.launch.yaml";

// The port a process said its view serves on ("view: open http://HOST:PORT/"), 0 until it did.
unsigned viewPort(const ChildProcess& process) {
  static const std::regex url(R"(view: open http://[0-9.]+:([0-9]+)/)");
  std::smatch match;
  const std::string err = process.currentErr();
  return std::regex_search(err, match, url) ? static_cast<unsigned>(std::stoul(match[1])) : 0u;
}

class ViewCli : public ::testing::Test {
 protected:
  ProcessOptions options(const std::string& name) {
    ProcessOptions result;
    result.output_dir = dir_.path() / name;
    std::filesystem::create_directories(result.output_dir);
    result.environment["SERVOLOOP_RUN_DIR"] = (dir_.path() / "run").string();
    return result;
  }
  TempDir dir_{"servoloop-view-cli"};
};

TEST_F(ViewCli, LaunchWithAViewAndAViewAttachingFromAnotherProcess) {
  ChildProcess launch({SERVOLOOP_CLI_EXE, "launch", kSeedLaunch, "--backend", "mock", "--view", "127.0.0.1:0"},
                      options("launch"));
  ASSERT_TRUE(servoloop::testing::waitUntil([&] { return viewPort(launch) != 0; }, std::chrono::seconds(30)))
      << launch.currentErr();
  const unsigned launch_port = viewPort(launch);
  const auto page = servoloop::testing::httpGet("127.0.0.1", launch_port, "/");
  EXPECT_EQ(page.status, 200);
  EXPECT_NE(page.body.find("three.min.js"), std::string::npos);

  // `servoloop view` in another process, on the same world.
  ChildProcess view({SERVOLOOP_CLI_EXE, "view", "127.0.0.1:0"}, options("view"));
  ASSERT_TRUE(servoloop::testing::waitUntil([&] { return viewPort(view) != 0; }, std::chrono::seconds(30)))
      << view.currentErr();
  for (const unsigned port : {launch_port, viewPort(view)}) {
    servoloop::testing::WsTestClient socket;
    ASSERT_TRUE(socket.connect("ws://127.0.0.1:" + std::to_string(port) + "/ws")) << socket.why();
    const json hello = nextOfType(socket, "hello", kMessageWait);
    EXPECT_FALSE(hello.value("control", true)) << "read-only unless --view-control";
    const json scene = nextOfType(socket, "scene", kMessageWait);
    ASSERT_TRUE(scene.is_object()) << port;
    ASSERT_EQ(scene["models"].size(), 1u);
    EXPECT_EQ(scene["models"][0]["ns"], "/one_DOF_robot");
    const json frame = nextOfType(socket, "frame", kMessageWait);
    ASSERT_TRUE(frame.is_object());
    EXPECT_EQ(frame["models"][0]["ns"], "/one_DOF_robot");
  }
  view.signal(SIGINT);
  EXPECT_EQ(view.wait(20.0).status, 0);
  launch.signal(SIGINT);
  EXPECT_EQ(launch.wait(30.0).status, 0);
}

TEST_F(ViewCli, APortInUseEndsTheLaunchWithOneErrorNamingIt) {
  const int taken = ::socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(taken, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(taken, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  ASSERT_EQ(::listen(taken, 1), 0);
  socklen_t length = sizeof address;
  ::getsockname(taken, reinterpret_cast<sockaddr*>(&address), &length);
  const std::string port = std::to_string(ntohs(address.sin_port));

  const auto result = servoloop::testing::runProcess(
      {SERVOLOOP_CLI_EXE, "launch", kSeedLaunch, "--backend", "mock", "--duration", "1", "--view", port},
      options("taken"), 60.0);
  ::close(taken);
  EXPECT_EQ(result.status, 1);
  EXPECT_NE(result.err.find("port " + port + " on 127.0.0.1 is in use"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("--view"), std::string::npos) << result.err;
  // Refused before the world was built: no robot was spawned.
  EXPECT_EQ(result.err.find("spawned robot"), std::string::npos) << result.err;
}

TEST_F(ViewCli, AnAddressOffThisMachineIsWarnedAboutAndControlNeedsAView) {
  const auto open = servoloop::testing::runProcess(
      {SERVOLOOP_CLI_EXE, "launch", kSeedLaunch, "--backend", "mock", "--duration", "0.5", "--view", "0.0.0.0:0"},
      options("open"), 60.0);
  EXPECT_EQ(open.status, 0) << open.err;
  EXPECT_NE(open.err.find("[W] view: serving on 0.0.0.0"), std::string::npos) << open.err;

  const auto control = servoloop::testing::runProcess(
      {SERVOLOOP_CLI_EXE, "launch", kSeedLaunch, "--backend", "mock", "--duration", "0.5", "--view-control"},
      options("control"), 60.0);
  EXPECT_EQ(control.status, 1);
  EXPECT_NE(control.err.find("--view-control: there is no view to control from; add --view"), std::string::npos)
      << control.err;

  const auto bad = servoloop::testing::runProcess({SERVOLOOP_CLI_EXE, "view", "8080x"}, options("bad"), 60.0);
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.err.find("view address '8080x'"), std::string::npos) << bad.err;
}

}  // namespace
