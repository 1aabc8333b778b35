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

#include "child_process.hpp"
#include "servoloop/ipc/ipc_connection.hpp"
#include "servoloop/ipc/ipc_server.hpp"
#include "temp_dir.hpp"

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
  const std::filesystem::path& scratch() const { return base_.path(); }

 private:
  servoloop::testing::TempDir base_{"servoloop-cli"};
  std::filesystem::path run_dir_;
};

// A node serving `node_name`'s socket. Ops without a handler answer ok with no
// fields (ping answers with its namespace).
class FakeNode {
 public:
  using Handler =
      std::function<nlohmann::json(const nlohmann::json& request,
                                   servoloop::ipc::IpcConnection& connection)>;

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
                        servoloop::ipc::IpcConnection& connection);

  std::string node_name_;
  mutable std::mutex mutex_;
  std::map<std::string, Handler> handlers_;
  std::vector<nlohmann::json> requests_;
  std::unique_ptr<servoloop::ipc::IpcServer> server_;
};

using CliResult = servoloop::testing::ProcessResult;
using servoloop::testing::lineCount;
using servoloop::testing::readFile;

// A running `servoloop` child process with stdout/stderr going to files in
// `scratch`.
class CliProcess : public servoloop::testing::ChildProcess {
 public:
  CliProcess(const std::vector<std::string>& args, const std::filesystem::path& scratch);
};

// Polls `done` every 20 ms until it returns true; false after timeout_s.
bool waitUntil(const std::function<bool()>& done, double timeout_s);

// Runs `servoloop args...` to completion (bounded by timeout_s).
CliResult runCli(const std::vector<std::string>& args, const std::filesystem::path& scratch,
                 double timeout_s = 20.0);

}  // namespace servoloop::cli::testing
