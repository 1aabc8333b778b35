#pragma once
// A program run as a child process for end-to-end tests: standard input from
// /dev/null, standard output and error captured in files of a folder the test
// owns, optional working folder and environment changes, and every wait
// bounded in time (a child still running at the bound is killed and reported
// as timed out). The one way tests start `servoloop`.
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace servoloop::testing {

struct ProcessResult {
  int status = -1;  // exit status; -1 when killed by a signal or timed out
  bool timed_out = false;
  std::string out;
  std::string err;
  double elapsed_s = 0.0;
};

struct ProcessOptions {
  // Where the captured stdout/stderr files go (required).
  std::filesystem::path output_dir;
  // Working folder of the child; the test's own when empty.
  std::filesystem::path working_dir;
  // Variables set (value) or removed (nullopt) in the child's environment.
  std::map<std::string, std::optional<std::string>> environment;
};

class ChildProcess {
 public:
  // argv[0] is the program's path.
  ChildProcess(const std::vector<std::string>& argv, const ProcessOptions& options);
  ~ChildProcess();  // kills a child still running
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  void signal(int signal_number);
  // Waits up to timeout_s for stdout to contain `text`; false on timeout or
  // when the child exits without having printed it.
  bool waitForOutput(const std::string& text, double timeout_s);
  // Waits up to timeout_s for the child to exit (then kills it).
  ProcessResult wait(double timeout_s);
  std::string currentOut() const;
  std::string currentErr() const;

 private:
  bool reap(bool block);

  pid_t pid_ = -1;
  int exit_status_ = -1;
  bool finished_ = false;
  std::filesystem::path out_path_;
  std::filesystem::path err_path_;
  std::chrono::steady_clock::time_point start_;
};

// Runs argv to completion, bounded by timeout_s.
ProcessResult runProcess(const std::vector<std::string>& argv, const ProcessOptions& options,
                         double timeout_s);

// Runs a /bin/sh command line to completion, bounded by timeout_s.
ProcessResult runShell(const std::string& command, const ProcessOptions& options,
                       double timeout_s);

int lineCount(const std::string& text);

}  // namespace servoloop::testing
