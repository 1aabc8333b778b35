// Socket location: naming, the private run directory and its refusals,
// listing nodes, stale sockets.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include "ipc_test_support.hpp"
#include "servoloop/ipc/ipc_client.hpp"
#include "servoloop/ipc/ipc_server.hpp"
#include "servoloop/ipc/ipc_socket_path.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::ipc {
namespace {

using testing::ScopedRunDir;

mode_t modeOf(const std::filesystem::path& path) {
  struct stat info {};
  EXPECT_EQ(::lstat(path.c_str(), &info), 0) << path;
  return info.st_mode & 07777;
}

std::string errorText(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  return "<no servoloop::Error thrown>";
}

IpcServer::Handler nullHandler() {
  return [](const nlohmann::json&, IpcConnection&) { return nlohmann::json(); };
}

// Restores an environment variable on scope exit.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value != nullptr) {
      ::setenv(name, value, 1);
    } else {
      ::unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (old_) {
      ::setenv(name_, old_->c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(IpcSocketPath, StemOfNodeName) {
  EXPECT_EQ(socketStemFor("/one_DOF_robot"), "one_DOF_robot");
  EXPECT_EQ(socketStemFor("one_DOF_robot"), "one_DOF_robot");
  EXPECT_EQ(socketStemFor("/"), "default");
  EXPECT_EQ(socketStemFor(""), "default");
  EXPECT_EQ(socketStemFor("//"), "default");
  EXPECT_EQ(socketStemFor("/arm/left/"), "arm.left");
  EXPECT_EQ(socketStemFor("/../etc passwd"), "__.etc_passwd");  // no path escapes
}

TEST(IpcSocketPath, NodeNameOfStemInvertsRosNames) {
  for (const char* name : {"/one_DOF_robot", "/arm/left", "/"}) {
    EXPECT_EQ(nodeNameForStem(socketStemFor(name)), name);
  }
  EXPECT_EQ(nodeNameForSocketPath("/x/y/one_DOF_robot.sock"), "/one_DOF_robot");
}

TEST(IpcSocketPath, RunDirectoryFollowsEnvironment) {
  {
    ScopedEnv run("SERVOLOOP_RUN_DIR", "/tmp/sl-test-run");
    ScopedEnv xdg("XDG_RUNTIME_DIR", "/run/user/4242");
    EXPECT_EQ(ipcRunDirectory(), "/tmp/sl-test-run");
    EXPECT_EQ(socketPathFor("/one_DOF_robot"), "/tmp/sl-test-run/one_DOF_robot.sock");
    EXPECT_EQ(socketPathFor("/"), "/tmp/sl-test-run/default.sock");
  }
  {
    ScopedEnv run("SERVOLOOP_RUN_DIR", nullptr);
    ScopedEnv xdg("XDG_RUNTIME_DIR", "/run/user/4242");
    EXPECT_EQ(ipcRunDirectory(), "/run/user/4242/servoloop");
  }
  {
    ScopedEnv run("SERVOLOOP_RUN_DIR", nullptr);
    ScopedEnv xdg("XDG_RUNTIME_DIR", nullptr);
    EXPECT_EQ(ipcRunDirectory(), "/tmp/servoloop-" + std::to_string(::geteuid()));
  }
}

TEST(IpcSocketPath, CreatesRunDirectoryWithMode0700WhateverTheUmask) {
  ScopedRunDir dir;
  const mode_t old_umask = ::umask(0);  // the widest umask must still give 0700
  ensurePrivateDirectory(dir.runDir());
  ::umask(old_umask);
  EXPECT_EQ(modeOf(dir.runDir()), 0700u);
  ensurePrivateDirectory(dir.runDir());  // an existing private directory is fine
  EXPECT_EQ(modeOf(dir.runDir()), 0700u);

  const std::filesystem::path nested = dir.base() / "a" / "b" / "run";
  ensurePrivateDirectory(nested);
  EXPECT_EQ(modeOf(nested), 0700u);
}

TEST(IpcSocketPath, ServerCreatesPrivateRunDirectory) {
  ScopedRunDir dir;
  ASSERT_FALSE(std::filesystem::exists(dir.runDir()));
  IpcServer server(socketPathFor("/one_DOF_robot"), nullHandler());
  server.start();
  EXPECT_EQ(modeOf(dir.runDir()), 0700u);
  EXPECT_TRUE(std::filesystem::is_socket(dir.runDir() / "one_DOF_robot.sock"));
  server.stop();
  EXPECT_FALSE(std::filesystem::exists(dir.runDir() / "one_DOF_robot.sock"));
}

TEST(IpcSocketPath, RefusesWorldWritableDirectory) {
  ScopedRunDir dir;
  ASSERT_EQ(::mkdir(dir.runDir().c_str(), 0700), 0);
  ASSERT_EQ(::chmod(dir.runDir().c_str(), 0777), 0);

  const std::string message = errorText([&] { ensurePrivateDirectory(dir.runDir()); });
  EXPECT_NE(message.find(dir.runDir().native()), std::string::npos) << message;
  EXPECT_NE(message.find("mode 0777"), std::string::npos) << message;
  EXPECT_NE(message.find("chmod 700"), std::string::npos) << message;
  EXPECT_EQ(modeOf(dir.runDir()), 0777u) << "the check must not silently change the directory";

  // Neither a server nor a client uses it.
  IpcServer server(socketPathFor("/one_DOF_robot"), nullHandler());
  EXPECT_NE(errorText([&] { server.start(); }).find("open to group/others"), std::string::npos);
  EXPECT_FALSE(server.isRunning());
  EXPECT_NE(errorText([] { IpcClient::connectToNode("/one_DOF_robot"); }).find("mode 0777"),
            std::string::npos);
  EXPECT_THROW(listNodes(), Error);
}

TEST(IpcSocketPath, RefusesGroupReadableDirectory) {
  ScopedRunDir dir;
  ASSERT_EQ(::mkdir(dir.runDir().c_str(), 0700), 0);
  ASSERT_EQ(::chmod(dir.runDir().c_str(), 0750), 0);
  EXPECT_NE(errorText([&] { ensurePrivateDirectory(dir.runDir()); }).find("mode 0750"), std::string::npos);
}

TEST(IpcSocketPath, RefusesDirectoryOwnedByAnotherUser) {
  ScopedRunDir dir;
  ASSERT_EQ(::mkdir(dir.runDir().c_str(), 0700), 0);
  const uid_t other_uid = ::geteuid() == 65534 ? 65533 : 65534;
  if (::chown(dir.runDir().c_str(), other_uid, static_cast<gid_t>(-1)) != 0) {
    GTEST_SKIP() << "changing a directory's owner needs root";
  }
  const std::string message = errorText([&] { ensurePrivateDirectory(dir.runDir()); });
  EXPECT_NE(message.find("owned by user id " + std::to_string(other_uid)), std::string::npos) << message;
  EXPECT_NE(message.find("SERVOLOOP_RUN_DIR"), std::string::npos) << message;
}

TEST(IpcSocketPath, RefusesSymlinkAndFile) {
  ScopedRunDir dir;
  const std::filesystem::path target = dir.base() / "elsewhere";
  ASSERT_EQ(::mkdir(target.c_str(), 0700), 0);
  std::filesystem::create_directory_symlink(target, dir.runDir());
  EXPECT_NE(errorText([&] { ensurePrivateDirectory(dir.runDir()); }).find("symbolic link"),
            std::string::npos);

  const std::filesystem::path file = dir.base() / "plain_file";
  std::ofstream(file) << "not a directory";
  EXPECT_NE(errorText([&] { ensurePrivateDirectory(file); }).find("not a directory"), std::string::npos);
}

TEST(IpcSocketPath, SocketPathTooLongNamesTheFix) {
  ScopedRunDir dir;
  const std::string long_name = "/" + std::string(120, 'r');
  IpcServer server(socketPathFor(long_name), nullHandler());
  const std::string message = errorText([&] { server.start(); });
  EXPECT_NE(message.find("SERVOLOOP_RUN_DIR"), std::string::npos) << message;
}

TEST(IpcSocketPath, ListNodesReportsLiveAndStaleSockets) {
  ScopedRunDir dir;
  EXPECT_TRUE(listNodes().empty()) << "no run directory yet: no nodes";

  IpcServer robot(socketPathFor("/one_DOF_robot"), nullHandler());
  IpcServer arm(socketPathFor("/arm/left"), nullHandler());
  robot.start();
  arm.start();

  // A stale socket: bound, never listened on, closed without removing the file.
  {
    IpcFd fd(::socket(AF_UNIX, SOCK_STREAM, 0));
    const sockaddr_un address = makeUnixAddress(dir.runDir() / "crashed.sock");
    ASSERT_EQ(::bind(fd.get(), reinterpret_cast<const sockaddr*>(&address), sizeof(address)), 0);
  }
  std::ofstream(dir.runDir() / "notes.txt") << "not a socket";

  const std::vector<IpcNodeEntry> nodes = listNodes();
  ASSERT_EQ(nodes.size(), 3u);
  EXPECT_EQ(nodes[0].node_name, "/arm/left");
  EXPECT_TRUE(nodes[0].accepting);
  EXPECT_EQ(nodes[1].node_name, "/crashed");
  EXPECT_FALSE(nodes[1].accepting);
  EXPECT_EQ(nodes[2].node_name, "/one_DOF_robot");
  EXPECT_EQ(nodes[2].socket_path, dir.runDir() / "one_DOF_robot.sock");
  EXPECT_TRUE(nodes[2].accepting);
}

}  // namespace
}  // namespace servoloop::ipc
