#pragma once
// The control_msgs/JointControllerState topic of a PID joint controller,
// published every 10th update as ros_control's effort controllers do: on the
// 1st, 11th, 21st, ... update after starting. Real-time safe except advertise().
#include <cstdint>
#include <string>

#include "servoloop/realtime/messages.hpp"
#include "servoloop/realtime/realtime_publisher.hpp"
#include "servoloop/controllers/pid.hpp"

namespace servoloop::realtime {
class TopicBus;
}

namespace servoloop::controllers {

class ControllerStatePublisher {
 public:
  using Message = servoloop::control_msgs::JointControllerState;
  static constexpr std::uint64_t kPublishEveryNthUpdate = 10;

  // Non-real-time. Nothing is published when bus is null.
  void advertise(servoloop::realtime::TopicBus* bus, const std::string& topic);

  // Real-time: the next update publishes (call from starting()).
  void reset() noexcept { updates_before_publish_ = 0; }

  // Real-time: call once per update. On the updates that publish, fill(msg)
  // writes the message (every field, it is reused) and it is published.
  template <class Fill>
  void onUpdate(Fill&& fill) noexcept {
    if (!countUpdate()) return;
    publish(fill);
  }

  // Real-time, the two halves of onUpdate, for a controller that keeps the
  // publishing out of its every-cycle code: countUpdate() once per update,
  // and when it says so, publish(fill).
  bool countUpdate() noexcept {
    if (updates_before_publish_ != 0) {
      --updates_before_publish_;
      return false;
    }
    updates_before_publish_ = kPublishEveryNthUpdate - 1;
    return true;
  }
  template <class Fill>
  void publish(Fill&& fill) noexcept {
    if (!publisher_.valid() || !publisher_.trylock()) return;
    fill(publisher_.msg());
    publisher_.unlockAndPublish();
  }

  // Real-time: copies the gains into msg (i_clamp is i_max, as in ros_control).
  static void setGains(Message& msg, const Pid::Gains& gains) noexcept {
    msg.p = gains.p_gain;
    msg.i = gains.i_gain;
    msg.d = gains.d_gain;
    msg.i_clamp = gains.i_max;
    msg.antiwindup = gains.antiwindup;
  }

  std::uint64_t publishedCount() const noexcept { return publisher_.publishedCount(); }
  const std::string& topic() const noexcept { return publisher_.topic(); }

 private:
  // First: the one member every update reads (countUpdate).
  std::uint64_t updates_before_publish_ = 0;  // updates until the next one that publishes
  servoloop::realtime::RealtimePublisher<Message> publisher_;
};

}  // namespace servoloop::controllers
