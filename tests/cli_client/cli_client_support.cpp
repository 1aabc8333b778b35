#include "cli_client_support.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <thread>

#include "servoloop/ipc/ipc_socket_path.hpp"

namespace servoloop::cli::testing {

namespace fs = std::filesystem;

ScopedRunDir::ScopedRunDir() : run_dir_(base_.path() / "run") {
  ::setenv("SERVOLOOP_RUN_DIR", run_dir_.c_str(), 1);
}

ScopedRunDir::~ScopedRunDir() { ::unsetenv("SERVOLOOP_RUN_DIR"); }

FakeNode::FakeNode(const std::string& node_name) : node_name_(node_name) {
  server_ = std::make_unique<servoloop::ipc::IpcServer>(
      servoloop::ipc::socketPathFor(node_name),
      [this](const nlohmann::json& request, servoloop::ipc::IpcConnection& connection) {
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
  on(op, [name, error](const nlohmann::json& request, servoloop::ipc::IpcConnection&) -> nlohmann::json {
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

nlohmann::json FakeNode::handle(const nlohmann::json& request, servoloop::ipc::IpcConnection& connection) {
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

CliProcess::CliProcess(const std::vector<std::string>& args, const fs::path& scratch)
    : ChildProcess(
          [&args] {
            std::vector<std::string> argv{SERVOLOOP_CLI_EXE};
            argv.insert(argv.end(), args.begin(), args.end());
            return argv;
          }(),
          servoloop::testing::ProcessOptions{scratch, {}, {}}) {}

bool waitUntil(const std::function<bool()>& done, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < deadline) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

CliResult runCli(const std::vector<std::string>& args, const fs::path& scratch, double timeout_s) {
  CliProcess process(args, scratch);
  return process.wait(timeout_s);
}

}  // namespace servoloop::cli::testing
