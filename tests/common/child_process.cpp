#include "child_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "temp_dir.hpp"

extern char** environ;

namespace servoloop::testing {

namespace fs = std::filesystem;

namespace {

std::string uniqueStem(const fs::path& dir) {
  static std::atomic<int> counter{0};
  return (dir / ("child" + std::to_string(::getpid()) + "_" + std::to_string(counter++))).string();
}

// The parent's environment with the requested changes.
std::vector<std::string> childEnvironment(
    const std::map<std::string, std::optional<std::string>>& changes) {
  std::vector<std::string> entries;
  for (char** entry = environ; *entry != nullptr; ++entry) {
    const std::string text(*entry);
    const std::string name = text.substr(0, text.find('='));
    if (changes.count(name) == 0) entries.push_back(text);
  }
  for (const auto& [name, value] : changes) {
    if (value) entries.push_back(name + "=" + *value);
  }
  return entries;
}

}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& argv_in, const ProcessOptions& options) {
  if (argv_in.empty()) throw std::invalid_argument("ChildProcess: empty argv");
  if (options.output_dir.empty()) throw std::invalid_argument("ChildProcess: no output folder");
  const std::string stem = uniqueStem(options.output_dir);
  out_path_ = stem + ".out";
  err_path_ = stem + ".err";

  std::vector<std::string> argv_strings = argv_in;
  std::vector<char*> argv;
  for (auto& arg : argv_strings) argv.push_back(arg.data());
  argv.push_back(nullptr);
  std::vector<std::string> env_strings = childEnvironment(options.environment);
  std::vector<char*> envp;
  for (auto& entry : env_strings) envp.push_back(entry.data());
  envp.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, out_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_addopen(&actions, 2, err_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  if (!options.working_dir.empty()) {
    posix_spawn_file_actions_addchdir_np(&actions, options.working_dir.c_str());
  }
  start_ = std::chrono::steady_clock::now();
  const int error = posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) {
    throw std::runtime_error("cannot start " + argv_strings[0] + ": " + std::strerror(error));
  }
}

ChildProcess::~ChildProcess() {
  if (!finished_ && pid_ > 0) {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
  }
}

void ChildProcess::signal(int signal_number) {
  if (!finished_) ::kill(pid_, signal_number);
}

std::string ChildProcess::currentOut() const { return readFile(out_path_); }
std::string ChildProcess::currentErr() const { return readFile(err_path_); }

bool ChildProcess::reap(bool block) {
  if (finished_) return true;
  int status = 0;
  const pid_t done = ::waitpid(pid_, &status, block ? 0 : WNOHANG);
  if (done != pid_) return false;
  finished_ = true;
  exit_status_ = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return true;
}

bool ChildProcess::waitForOutput(const std::string& text, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < deadline) {
    if (currentOut().find(text) != std::string::npos) return true;
    if (reap(false)) return currentOut().find(text) != std::string::npos;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

ProcessResult ChildProcess::wait(double timeout_s) {
  ProcessResult result;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!reap(false)) {
    if (std::chrono::steady_clock::now() >= deadline) {
      ::kill(pid_, SIGKILL);
      reap(true);
      exit_status_ = -1;
      result.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  result.status = exit_status_;
  result.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  result.out = readFile(out_path_);
  result.err = readFile(err_path_);
  return result;
}

ProcessResult runProcess(const std::vector<std::string>& argv, const ProcessOptions& options,
                         double timeout_s) {
  ChildProcess process(argv, options);
  return process.wait(timeout_s);
}

ProcessResult runShell(const std::string& command, const ProcessOptions& options, double timeout_s) {
  return runProcess({"/bin/sh", "-c", command}, options, timeout_s);
}

int lineCount(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

}  // namespace servoloop::testing
