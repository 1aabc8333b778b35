#pragma once
// servoloop's one logging facility (spdlog underneath, kept out of this
// header), with levels. Never call it on the real-time path: real-time code
// reports through ReturnType or lock-free status, and non-real-time code logs
// here.
//   servoloop::logger().warn("robot '{}': {}", name, why);
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/core.h>

namespace spdlog {
class logger;
}

namespace servoloop {

enum class LogLevel { trace, debug, info, warn, error, critical, off };

// The shared "servoloop" logger, writing to stderr. Its level starts from the
// SERVOLOOP_LOG_LEVEL environment variable (trace, debug, info, warn, error,
// off), default info. Messages are formatted with fmt only when their level is
// enabled.
class Logger {
 public:
  template <class... Args>
  void trace(fmt::format_string<Args...> format, Args&&... args) {
    log(LogLevel::trace, format, fmt::make_format_args(args...));
  }
  template <class... Args>
  void debug(fmt::format_string<Args...> format, Args&&... args) {
    log(LogLevel::debug, format, fmt::make_format_args(args...));
  }
  template <class... Args>
  void info(fmt::format_string<Args...> format, Args&&... args) {
    log(LogLevel::info, format, fmt::make_format_args(args...));
  }
  template <class... Args>
  void warn(fmt::format_string<Args...> format, Args&&... args) {
    log(LogLevel::warn, format, fmt::make_format_args(args...));
  }
  template <class... Args>
  void error(fmt::format_string<Args...> format, Args&&... args) {
    log(LogLevel::error, format, fmt::make_format_args(args...));
  }
  template <class... Args>
  void critical(fmt::format_string<Args...> format, Args&&... args) {
    log(LogLevel::critical, format, fmt::make_format_args(args...));
  }

  bool shouldLog(LogLevel level) const noexcept;
  // Logs text as it is (no formatting); logger().warn("{}", text) does the same.
  void write(LogLevel level, std::string_view text);

 private:
  // Never throws: a message that cannot be formatted (or no memory for it) is
  // logged as its format text, or dropped.
  void log(LogLevel level, fmt::string_view format, fmt::format_args args) noexcept {
    if (!shouldLog(level)) return;
    try {
      write(level, fmt::vformat(format, args));
    } catch (...) {
      writeUnformatted(level, format);
    }
  }
  void writeUnformatted(LogLevel level, fmt::string_view format) noexcept;
};

Logger& logger();

// The spdlog logger underneath, for code that adds sinks or changes its level
// directly (tests capturing the log); include <spdlog/spdlog.h> to use it.
spdlog::logger& spdlogLogger();

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
