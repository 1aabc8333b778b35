#pragma once
// Test support for the client commands: a fake node (an IpcServer answering
// the ops from node_operations.md with scripted handlers and recording every
// request), a private temporary run directory, and the built `servoloop`
// executable run as a child process with its output captured.
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "servoloop/controller_manager/ipc_connection.hpp"
#include "servoloop/controller_manager/ipc_server.hpp"

namespace servoloop::cli::testing {

// SERVOLOOP_RUN_DIR set to a fresh private directory for the test's lifetime
// (child processes inherit it).
class ScopedRunDir {
 public:
  ScopedRunDir();
  ~ScopedRunDir();
  ScopedRunDir(const ScopedRunDir&) = delete;
  ScopedRunDir& operator=(const ScopedRunDir&) = delete;
  const std::filesystem::path& runDir() const { return run_dir_; }
  // A scratch folder for test files (not the run directory).
  const std::filesystem::path& scratch() const { return base_; }

 private:
  std::filesystem::path base_;
  std::filesystem::path run_dir_;
};

// A node serving `node_name`'s socket. Ops without a handler answer ok with no
// fields (ping answers with its namespace).
class FakeNode {
 public:
  using Handler =
      std::function<nlohmann::json(const nlohmann::json& request,
                                   controller_manager::IpcConnection& connection)>;

  explicit FakeNode(const std::string& node_name);
  ~FakeNode();

  void on(const std::string& op, Handler handler);
  // Shorthand: `op` fails with `error` when the request's field `name` is `value`.
  void failWhen(const std::string& op, const std::string& name, const std::string& error);

  std::vector<nlohmann::json> requests() const;
  std::vector<std::string> ops() const;
  // Requests with this op, in order.
  std::vector<nlohmann::json> requestsFor(const std::string& op) const;

 private:
  nlohmann::json handle(const nlohmann::json& request,
                        controller_manager::IpcConnection& connection);

  std::string node_name_;
  mutable std::mutex mutex_;
  std::map<std::string, Handler> handlers_;
  std::vector<nlohmann::json> requests_;
  std::unique_ptr<controller_manager::IpcServer> server_;
};

struct CliResult {
  int status = -1;  // exit status; -1 if killed by a signal or timed out
  bool timed_out = false;
  std::string out;
  std::string err;
  double elapsed_s = 0.0;
};

// A running `servoloop` child process with stdout/stderr going to files.
class CliProcess {
 public:
  CliProcess(const std::vector<std::string>& args, const std::filesystem::path& scratch);
  ~CliProcess();
  CliProcess(const CliProcess&) = delete;
  CliProcess& operator=(const CliProcess&) = delete;

  void signal(int signal_number);
  // Waits up to `timeout_s` for stdout to contain `text`; false on timeout or exit.
  bool waitForOutput(const std::string& text, double timeout_s);
  // Waits up to `timeout_s` for exit (then kills it and sets timed_out).
  CliResult wait(double timeout_s);
  std::string currentOut() const;

 private:
  pid_t pid_ = -1;
  std::filesystem::path out_path_;
  std::filesystem::path err_path_;
  std::chrono::steady_clock::time_point start_;
  bool finished_ = false;
};

// Runs `servoloop args...` to completion (bounded by timeout_s).
CliResult runCli(const std::vector<std::string>& args, const std::filesystem::path& scratch,
                 double timeout_s = 20.0);

std::string readFile(const std::filesystem::path& path);
int lineCount(const std::string& text);

}  // namespace servoloop::cli::testing
