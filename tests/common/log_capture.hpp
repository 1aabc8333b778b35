#pragma once
// Captures what servoloop's logger writes while it is alive, for tests that
// check a warning was given (and given once).
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <cstddef>
#include <memory>
#include <sstream>
#include <string>

#include "servoloop/core/logging.hpp"

namespace servoloop::test {

class LogCapture {
 public:
  LogCapture() : sink_(std::make_shared<spdlog::sinks::ostream_sink_mt>(stream_)) {
    spdlogLogger().sinks().push_back(sink_);
  }
  ~LogCapture() {
    auto& sinks = spdlogLogger().sinks();
    for (auto it = sinks.begin(); it != sinks.end(); ++it) {
      if (*it == sink_) {
        sinks.erase(it);
        break;
      }
    }
  }
  LogCapture(const LogCapture&) = delete;
  LogCapture& operator=(const LogCapture&) = delete;

  std::string text() {
    spdlogLogger().flush();
    return stream_.str();
  }
  // How many times `needle` occurs in what was logged.
  std::size_t count(const std::string& needle) {
    const std::string all = text();
    std::size_t n = 0;
    for (auto at = all.find(needle); at != std::string::npos; at = all.find(needle, at + needle.size())) ++n;
    return n;
  }

 private:
  std::ostringstream stream_;
  std::shared_ptr<spdlog::sinks::ostream_sink_mt> sink_;
};

}  // namespace servoloop::test
