#include "servoloop/controllers/common/command_input.hpp"

#include <algorithm>
#include <cmath>

#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::controllers {


namespace {
bool allFinite(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}
}  // namespace

void ScalarCommandInput::connect(servoloop::realtime::TopicBus* bus, const std::string& topic,
                                 const std::string& controller_name) {
  topic_ = topic;
  if (bus == nullptr) return;
  input_ = bus->commandInput<servoloop::std_msgs::Float64>(topic);
  // Runs on the delivery thread: it may log. Only the first bad command is
  // logged, so a publisher stuck on NaN does not flood the log.
  auto logged = std::make_shared<std::atomic<bool>>(false);
  checker_ = bus->subscribe<servoloop::std_msgs::Float64>(
      topic, [topic, controller_name, logged](const servoloop::std_msgs::Float64& msg) {
        if (!std::isfinite(msg.data) && !logged->exchange(true)) {
          logger().warn("controller '{}': ignoring non-finite command {} on {} (the previous "
                        "command stays; further ones are only counted)",
                        controller_name, msg.data, topic);
        }
      });
}

bool ScalarCommandInput::takeNew(double& value) noexcept {
  if (!input_.hasNewMessage()) return false;
  const servoloop::std_msgs::Float64* msg = input_.latest();
  if (msg == nullptr) return false;
  if (!std::isfinite(msg->data)) {
    rejected_->non_finite.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  value = msg->data;
  return true;
}

void ArrayCommandInput::connect(servoloop::realtime::TopicBus* bus, const std::string& topic, std::size_t size,
                                const std::string& controller_name) {
  topic_ = topic;
  size_ = size;
  if (bus == nullptr) return;
  servoloop::std_msgs::Float64MultiArray prototype;
  prototype.data.assign(size, 0.0);
  input_ = bus->commandInput<servoloop::std_msgs::Float64MultiArray>(topic, prototype);
  auto logged_size = std::make_shared<std::atomic<bool>>(false);
  auto logged_non_finite = std::make_shared<std::atomic<bool>>(false);
  checker_ = bus->subscribe<servoloop::std_msgs::Float64MultiArray>(
      topic, [topic, controller_name, size, logged_size,
              logged_non_finite](const servoloop::std_msgs::Float64MultiArray& msg) {
        if (msg.data.size() != size) {
          if (!logged_size->exchange(true)) {
            logger().warn("controller '{}': ignoring a command with {} values on {}: it drives {} "
                          "joints and needs exactly {} (further ones are only counted)",
                          controller_name, msg.data.size(), topic, size, size);
          }
        } else if (!allFinite(msg.data) && !logged_non_finite->exchange(true)) {
          logger().warn("controller '{}': ignoring a command with a non-finite value on {} (the "
                        "previous command stays; further ones are only counted)",
                        controller_name, topic);
        }
      });
}

bool ArrayCommandInput::takeNew(std::vector<double>& values) noexcept {
  if (!input_.hasNewMessage()) return false;
  const servoloop::std_msgs::Float64MultiArray* msg = input_.latest();
  if (msg == nullptr) return false;
  if (msg->data.size() != size_ || values.size() != size_) {
    rejected_->wrong_size.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  if (!allFinite(msg->data)) {
    rejected_->non_finite.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  std::copy(msg->data.begin(), msg->data.end(), values.begin());
  return true;
}

}  // namespace servoloop::controllers
