#include "servoloop/core/logging.hpp"

#include <cstdlib>
#include <memory>
#include <string>

#include <spdlog/sinks/stdout_color_sinks.h>

#include "servoloop/core/errors.hpp"

namespace servoloop {
namespace {
std::shared_ptr<spdlog::logger> makeLogger() {
  auto sink = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
  auto log = std::make_shared<spdlog::logger>("servoloop", sink);
  log->set_pattern("[%L] %v");
  log->set_level(spdlog::level::info);
  if (const char* env = std::getenv("SERVOLOOP_LOG_LEVEL")) {
    const auto level = spdlog::level::from_str(env);
    // from_str answers "off" for unknown names; only accept a real "off".
    if (level != spdlog::level::off || std::string(env) == "off") log->set_level(level);
  }
  return log;
}
}  // namespace

spdlog::logger& logger() {
  static std::shared_ptr<spdlog::logger> instance = makeLogger();
  return *instance;
}

void setLogLevel(std::string_view level) {
  const std::string name(level);
  const auto parsed = spdlog::level::from_str(name);
  if (parsed == spdlog::level::off && name != "off") {
    throw Error("unknown log level '" + name +
                "'; use one of trace, debug, info, warn, error, off");
  }
  logger().set_level(parsed);
}

}  // namespace servoloop
