#include "servoloop/core/logging.hpp"

#include <cstdlib>
#include <memory>
#include <string>

#include <spdlog/details/null_mutex.h>
#include <spdlog/spdlog.h>
#include <spdlog/sinks/base_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>

#include "servoloop/core/errors.hpp"

namespace servoloop {
namespace {
// The innermost ThreadLogCapture of this thread, if any.
thread_local ThreadLogCapture* t_capture = nullptr;

// Hands warnings and errors to the calling thread's capture. Each thread
// touches only its own capture, so the sink needs no lock.
class CaptureSink final : public spdlog::sinks::base_sink<spdlog::details::null_mutex> {
 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    if (t_capture == nullptr || msg.level < spdlog::level::warn) return;
    t_capture->add(std::string(msg.payload.begin(), msg.payload.end()));
  }
  void flush_() override {}
};

std::shared_ptr<spdlog::logger> makeLogger() {
  const spdlog::sinks_init_list sinks = {std::make_shared<spdlog::sinks::stderr_color_sink_mt>(),
                                         std::make_shared<CaptureSink>()};
  auto log = std::make_shared<spdlog::logger>("servoloop", sinks);
  log->set_pattern("[%L] %v");
  log->set_level(spdlog::level::info);
  if (const char* env = std::getenv("SERVOLOOP_LOG_LEVEL")) {
    const auto level = spdlog::level::from_str(env);
    // from_str answers "off" for unknown names; only accept a real "off".
    if (level != spdlog::level::off || std::string(env) == "off") log->set_level(level);
  }
  return log;
}

constexpr spdlog::level::level_enum toSpdlog(LogLevel level) {
  switch (level) {
    case LogLevel::trace: return spdlog::level::trace;
    case LogLevel::debug: return spdlog::level::debug;
    case LogLevel::info: return spdlog::level::info;
    case LogLevel::warn: return spdlog::level::warn;
    case LogLevel::error: return spdlog::level::err;
    case LogLevel::critical: return spdlog::level::critical;
    case LogLevel::off: return spdlog::level::off;
  }
  return spdlog::level::off;
}
}  // namespace

spdlog::logger& spdlogLogger() {
  static std::shared_ptr<spdlog::logger> instance = makeLogger();
  return *instance;
}

Logger& logger() {
  static Logger instance;
  return instance;
}

bool Logger::shouldLog(LogLevel level) const noexcept { return spdlogLogger().should_log(toSpdlog(level)); }

void Logger::write(LogLevel level, std::string_view text) { spdlogLogger().log(toSpdlog(level), text); }

void Logger::writeUnformatted(LogLevel level, fmt::string_view format) noexcept {
  try {
    write(level, std::string_view(format.data(), format.size()));
  } catch (...) {
    // Nothing is left to report it with.
  }
}

ThreadLogCapture::ThreadLogCapture() : outer_(t_capture) { t_capture = this; }

ThreadLogCapture::~ThreadLogCapture() { t_capture = outer_; }

void setLogLevel(std::string_view level) {
  const std::string name(level);
  const auto parsed = spdlog::level::from_str(name);
  if (parsed == spdlog::level::off && name != "off") {
    throw Error("unknown log level '" + name +
                "'; use one of trace, debug, info, warn, error, off");
  }
  spdlogLogger().set_level(parsed);
}

}  // namespace servoloop
