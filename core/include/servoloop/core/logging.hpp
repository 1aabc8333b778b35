#pragma once
// servoloop's one logging facility (spdlog underneath), with levels. Never call
// it on the real-time path: real-time code reports through ReturnType or
// lock-free status, and non-real-time code logs here.
#include <string_view>

#include <spdlog/spdlog.h>

namespace servoloop {

// The shared "servoloop" logger, writing to stderr. Its level starts from the
// SERVOLOOP_LOG_LEVEL environment variable (trace, debug, info, warn, error,
// off), default info.
spdlog::logger& logger();

// Sets the level by name; unknown names throw servoloop::Error listing the valid ones.
void setLogLevel(std::string_view level);

}  // namespace servoloop
