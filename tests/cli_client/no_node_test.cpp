// With no node running, every client command says so in one line, whatever a
// node that ended left in the run directory: its .lock file (kept on purpose,
// docs/ipc_protocol.md) or, after a crash, a socket file nobody accepts on.
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_client_support.hpp"

namespace servoloop::cli::testing {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

// A socket file bound and closed without unlinking: what a killed node leaves.
void leaveStaleSocket(const std::filesystem::path& path) {
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::strncpy(address.sun_path, path.c_str(), sizeof(address.sun_path) - 1);
  ASSERT_EQ(::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)), 0) << std::strerror(errno);
  ::close(fd);
  ASSERT_TRUE(std::filesystem::is_socket(path));
}

int occurrences(const std::string& text, const std::string& part) {
  int count = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + part.size())) ++count;
  return count;
}

class NoNodeTest : public ::testing::Test {
 protected:
  // Every command that needs a node, each expected to fail with one line.
  void expectEveryCommandSaysNoNodeRuns() {
    const std::vector<std::vector<std::string>> commands = {
        {"topic", "list"},
        {"topic", "list", "--json"},
        {"topic", "list", "--namespace", "/one_DOF_robot"},
        {"topic", "echo", "-n", "1", "/one_DOF_robot/joint_states"},
        {"control", "list"},
        {"control", "list", "--namespace", "/one_DOF_robot"},
        {"plot", "--topic", "/one_DOF_robot/joint_states", "-n", "1", "-o", "x.png"},
    };
    for (const auto& command : commands) {
      const std::string text = command[0] + " " + command[1] + (command.size() > 2 ? " " + command[2] : "");
      const CliResult result = runCli(command, run_dir_.scratch());
      EXPECT_EQ(result.status, 1) << text;
      EXPECT_EQ(lineCount(result.err), 1) << text << ": " << result.err;
      EXPECT_THAT(result.err, HasSubstr(": error: no servoloop node is running")) << text;
      EXPECT_THAT(result.err, HasSubstr("servoloop launch")) << text;
      EXPECT_THAT(result.err, HasSubstr(run_dir_.runDir().string())) << text;
      // Said once, and nothing about the files a node leaves behind (a
      // socket path there reads as if that file were the problem).
      EXPECT_EQ(occurrences(result.err, "no servoloop node"), 1) << text << ": " << result.err;
      EXPECT_THAT(result.err, ::testing::Not(HasSubstr(".sock"))) << text;
      EXPECT_THAT(result.err, ::testing::Not(HasSubstr(".lock"))) << text;
      EXPECT_THAT(result.err, ::testing::Not(HasSubstr("stale"))) << text;
      EXPECT_TRUE(result.out.empty()) << text << ": " << result.out;
    }
  }

  ScopedRunDir run_dir_;
};

TEST_F(NoNodeTest, AfterANodeEndedAndLeftItsLockFile) {
  { FakeNode node("/one_DOF_robot"); }
  ASSERT_TRUE(std::filesystem::exists(run_dir_.runDir() / "one_DOF_robot.lock"));
  ASSERT_FALSE(std::filesystem::exists(run_dir_.runDir() / "one_DOF_robot.sock"));
  expectEveryCommandSaysNoNodeRuns();
}

TEST_F(NoNodeTest, AfterANodeDiedAndLeftItsSocketFile) {
  { FakeNode node("/one_DOF_robot"); }
  leaveStaleSocket(run_dir_.runDir() / "one_DOF_robot.sock");
  expectEveryCommandSaysNoNodeRuns();
}

TEST_F(NoNodeTest, WhenNoNodeEverRan) {
  ASSERT_FALSE(std::filesystem::exists(run_dir_.runDir()));
  expectEveryCommandSaysNoNodeRuns();
}

}  // namespace
}  // namespace servoloop::cli::testing
