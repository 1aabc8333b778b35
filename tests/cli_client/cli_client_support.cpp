#include "cli_client_support.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "servoloop/controller_manager/ipc_socket_path.hpp"

extern char** environ;

namespace servoloop::cli::testing {

namespace fs = std::filesystem;
namespace cm = servoloop::controller_manager;

ScopedRunDir::ScopedRunDir() {
  char pattern[] = "/tmp/slcli-XXXXXX";
  const char* made = ::mkdtemp(pattern);
  if (made == nullptr) throw std::runtime_error("mkdtemp failed");
  base_ = made;
  run_dir_ = base_ / "run";
  ::setenv("SERVOLOOP_RUN_DIR", run_dir_.c_str(), 1);
}

ScopedRunDir::~ScopedRunDir() {
  ::unsetenv("SERVOLOOP_RUN_DIR");
  std::error_code ignored;
  fs::remove_all(base_, ignored);
}

FakeNode::FakeNode(const std::string& node_name) : node_name_(node_name) {
  server_ = std::make_unique<cm::IpcServer>(
      cm::socketPathFor(node_name),
      [this](const nlohmann::json& request, cm::IpcConnection& connection) {
        return handle(request, connection);
      });
  server_->start();
}

FakeNode::~FakeNode() { server_->stop(); }

void FakeNode::on(const std::string& op, Handler handler) {
  std::lock_guard lock(mutex_);
  handlers_[op] = std::move(handler);
}

void FakeNode::failWhen(const std::string& op, const std::string& name, const std::string& error) {
  on(op, [name, error](const nlohmann::json& request, cm::IpcConnection&) -> nlohmann::json {
    if (request.value("name", "") == name) return {{"ok", false}, {"error", error}};
    return nullptr;
  });
}

std::vector<nlohmann::json> FakeNode::requests() const {
  std::lock_guard lock(mutex_);
  return requests_;
}

std::vector<std::string> FakeNode::ops() const {
  std::vector<std::string> ops;
  for (const auto& request : requests()) ops.push_back(request["op"]);
  return ops;
}

std::vector<nlohmann::json> FakeNode::requestsFor(const std::string& op) const {
  std::vector<nlohmann::json> matching;
  for (const auto& request : requests()) {
    if (request["op"] == op) matching.push_back(request);
  }
  return matching;
}

nlohmann::json FakeNode::handle(const nlohmann::json& request, cm::IpcConnection& connection) {
  Handler handler;
  {
    std::lock_guard lock(mutex_);
    requests_.push_back(request);
    const auto found = handlers_.find(request["op"].get<std::string>());
    if (found != handlers_.end()) handler = found->second;
  }
  if (handler) return handler(request, connection);
  if (request["op"] == "ping") {
    return {{"namespace", node_name_}, {"sim_time", 0.0}, {"robots", {node_name_}}};
  }
  return nullptr;
}

namespace {

std::string uniqueName(const fs::path& scratch, const char* suffix) {
  static int counter = 0;
  return (scratch / ("cli" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + suffix))
      .string();
}

}  // namespace

CliProcess::CliProcess(const std::vector<std::string>& args, const fs::path& scratch)
    : out_path_(uniqueName(scratch, ".out")), err_path_(uniqueName(scratch, ".err")) {
  std::vector<std::string> argv_strings{SERVOLOOP_CLI_EXE};
  argv_strings.insert(argv_strings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& arg : argv_strings) argv.push_back(arg.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, out_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0600);
  posix_spawn_file_actions_addopen(&actions, 2, err_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0600);
  start_ = std::chrono::steady_clock::now();
  const int error = posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) throw std::runtime_error("cannot start " + argv_strings[0]);
}

CliProcess::~CliProcess() {
  if (!finished_ && pid_ > 0) {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
  }
}

void CliProcess::signal(int signal_number) { ::kill(pid_, signal_number); }

std::string CliProcess::currentOut() const { return readFile(out_path_); }

bool CliProcess::waitForOutput(const std::string& text, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < deadline) {
    if (currentOut().find(text) != std::string::npos) return true;
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) {
      finished_ = true;
      return currentOut().find(text) != std::string::npos;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

CliResult CliProcess::wait(double timeout_s) {
  CliResult result;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  int status = 0;
  while (!finished_) {
    const pid_t done = ::waitpid(pid_, &status, WNOHANG);
    if (done == pid_) {
      finished_ = true;
      result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      break;
    }
    if (std::chrono::steady_clock::now() >= deadline) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
      finished_ = true;
      result.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  result.elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  result.out = readFile(out_path_);
  result.err = readFile(err_path_);
  return result;
}

CliResult runCli(const std::vector<std::string>& args, const fs::path& scratch, double timeout_s) {
  CliProcess process(args, scratch);
  return process.wait(timeout_s);
}

std::string readFile(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

int lineCount(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

}  // namespace servoloop::cli::testing
