#include "servoloop/controllers/common/command_timeout.hpp"

#include <cmath>

#include "servoloop/controllers/common/controller_params.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/realtime/topic_bus.hpp"

namespace servoloop::controllers {

void CommandTimeout::init(const controller_manager::ControllerContext& context, const std::string& fallback,
                          const std::string& parameter, double default_s, const std::string& command_topic) {
  timeout_s_ = optionalNumber(context, parameter, default_s);
  if (!(timeout_s_ >= 0.0)) {
    throw ConfigError("controller '" + context.name + "': " + parameterPath(context, parameter) + " is " +
                      std::to_string(timeout_s_) +
                      "; give the seconds without a command after which it stops (0: never)");
  }
  if (timeout_s_ == 0.0 || context.topics == nullptr) return;
  const std::string topic = controllerTopic(context, "command_timed_out");
  publisher_ = context.topics->advertise<servoloop::std_msgs::Float64>(topic);
  auto logged = std::make_shared<std::atomic<bool>>(false);
  reporter_ = context.topics->subscribe<servoloop::std_msgs::Float64>(
      topic, [name = context.name, command = controllerTopic(context, command_topic), timeout = timeout_s_, fallback,
              parameter, topic, logged](const servoloop::std_msgs::Float64& msg) {
        if (logged->exchange(true)) return;
        logger().warn("controller '{}': no command on {} for {} s ({}) at t = {} s: {} until the next "
                      "one (further timeouts are published on {})",
                      name, command, timeout, parameter, msg.data, fallback, topic);
      });
}

bool CommandTimeout::expired(const Time& time) noexcept {
  // (Control times are step counts times the step: a nanosecond of slack
  // keeps a timeout of k steps from landing one step late.)
  if (timeout_s_ <= 0.0 || timed_out_ || time.seconds - last_command_.seconds < timeout_s_ - 1e-9) return false;
  timed_out_ = true;
  timeouts_.fetch_add(1, std::memory_order_relaxed);
  if (publisher_.valid()) publisher_.publish(servoloop::std_msgs::Float64{time.seconds});
  return true;
}

}  // namespace servoloop::controllers
