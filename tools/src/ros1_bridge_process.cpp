#include "ros1_bridge_process.hpp"

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/executable_path.hpp"

extern char** environ;

namespace servoloop::cli {
namespace {

namespace fs = std::filesystem;

fs::path programDirectory() {
  std::error_code error;
  fs::path directory = servoloop::executableDirectory(error);
  if (error) throw Error("cannot find the servoloop executable (/proc/self/exe): " + error.message());
  return directory;
}

// Waits up to timeout_s for `pid` to end; true once it has.
bool reapWithin(pid_t pid, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (true) {
    int status = 0;
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid || (done < 0 && errno == ECHILD)) return true;
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace

fs::path ros1BridgeProgram() {
  const fs::path bridge = programDirectory() / "servoloop_ros1_bridge";
  if (!fs::exists(bridge)) {
    throw Error("the ROS 1 bridge is not part of this build (" + bridge.string() +
                " is missing): install Debian's ROS 1 packages (bash scripts/install_ros1.sh) and build again; "
                "cmake finds them (docs/ros1.md)");
  }
  return bridge;
}

fs::path ros1PythonPath() {
  return (programDirectory() / ".." / "share" / "servoloop" / "ros1" / "python").lexically_normal();
}

void Ros1BridgeProcesses::start(const std::string& robot_namespace) {
  std::string program = ros1BridgeProgram().string();
  std::string flag = "--namespace";
  std::string ns = robot_namespace;
  char* argv[] = {program.data(), flag.data(), ns.data(), nullptr};
  pid_t pid = -1;
  const int error = ::posix_spawn(&pid, program.c_str(), nullptr, nullptr, argv, environ);
  if (error != 0) throw Error("cannot start " + program + ": " + std::strerror(error));
  children_.push_back(pid);
}

Ros1BridgeProcesses::~Ros1BridgeProcesses() { stop(); }

void Ros1BridgeProcesses::stop() {
  for (pid_t pid : children_) ::kill(pid, SIGINT);
  for (pid_t pid : children_) {
    if (!reapWithin(pid, 15.0)) {
      ::kill(pid, SIGKILL);
      reapWithin(pid, 5.0);
    }
  }
  children_.clear();
}

}  // namespace servoloop::cli
