#pragma once
// servoloop's one logging facility (spdlog underneath), with levels. Never call
// it on the real-time path: real-time code reports through ReturnType or
// lock-free status, and non-real-time code logs here.
#include <string>
#include <string_view>
#include <vector>

#include <spdlog/spdlog.h>

namespace servoloop {

// The shared "servoloop" logger, writing to stderr. Its level starts from the
// SERVOLOOP_LOG_LEVEL environment variable (trace, debug, info, warn, error,
// off), default info.
spdlog::logger& logger();

// Sets the level by name; unknown names throw servoloop::Error listing the valid ones.
void setLogLevel(std::string_view level);

// While one lives, the warnings and errors its thread logs are also kept in
// it (they are logged as usual too), e.g. to hand a spawn's warnings back to
// the client that asked for it. Captures on one thread nest: the innermost
// one keeps them.
class ThreadLogCapture {
 public:
  ThreadLogCapture();
  ~ThreadLogCapture();
  ThreadLogCapture(const ThreadLogCapture&) = delete;
  ThreadLogCapture& operator=(const ThreadLogCapture&) = delete;

  const std::vector<std::string>& warnings() const noexcept { return warnings_; }
  void add(std::string text) { warnings_.push_back(std::move(text)); }

 private:
  std::vector<std::string> warnings_;
  ThreadLogCapture* outer_;
};

}  // namespace servoloop
