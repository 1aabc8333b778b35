#pragma once
// A forward-command controller's `command_timeout`: when no usable command
// arrived for that many seconds of control time, the controller falls back to
// a safe command (zero effort or velocity, or holding the position it
// measures then) until the next one arrives. Each timeout is published, off
// the real-time path, on <robot ns>/<controller>/command_timed_out
// (std_msgs/Float64: the control time it happened), and the first one is
// logged as a warning by a subscriber on the bus's delivery thread.
//
// Parameter: command_timeout (s, finite, >= 0; default 0: never times out), or
// the name and default the controller gives.
#include <atomic>
#include <cstdint>
#include <string>

#include "servoloop/controller_manager/controller_context.hpp"
#include "servoloop/core/time.hpp"
#include "servoloop/realtime/messages.hpp"
#include "servoloop/realtime/realtime_publisher.hpp"
#include "servoloop/realtime/topic_subscription.hpp"

namespace servoloop::controllers {

class CommandTimeout {
 public:
  CommandTimeout() = default;
  CommandTimeout(const CommandTimeout&) = delete;
  CommandTimeout& operator=(const CommandTimeout&) = delete;

  // Non-real-time. Reads `parameter` (a diff drive's is cmd_vel_timeout, for
  // commands on its cmd_vel topic); fallback says what the controller does on
  // a timeout, for the log ("the effort command goes to 0"). Throws
  // servoloop::ConfigError for a value that is not a finite number >= 0.
  void init(const controller_manager::ControllerContext& context, const std::string& fallback,
            const std::string& parameter = "command_timeout", double default_s = 0.0,
            const std::string& command_topic = "command");

  // Real-time: the clock starts again (a controller's starting(), or a command).
  void restart(const Time& time) noexcept {
    last_command_ = time;
    timed_out_ = false;
  }

  // Real-time: nothing times out until the next restart() (a controller that
  // starts with nothing to keep doing: no warning before the first command).
  void disarm() noexcept { timed_out_ = true; }

  // Real-time: true in the one cycle the timeout is reached (the controller
  // then writes its fallback command, which stays until a command arrives).
  bool expired(const Time& time) noexcept;

  double seconds() const noexcept { return timeout_s_; }
  std::uint64_t count() const noexcept { return timeouts_.load(std::memory_order_relaxed); }

 private:
  double timeout_s_ = 0.0;
  Time last_command_{};
  bool timed_out_ = false;
  std::atomic<std::uint64_t> timeouts_{0};
  servoloop::realtime::RealtimePublisher<servoloop::std_msgs::Float64> publisher_;
  servoloop::realtime::Subscription reporter_;  // logs the first timeout, off the real-time thread
};

}  // namespace servoloop::controllers
