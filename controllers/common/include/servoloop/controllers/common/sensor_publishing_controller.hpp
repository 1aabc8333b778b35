#pragma once
// The shape ros_controllers' sensor controllers share (imu_sensor_controller,
// force_torque_sensor_controller): one real-time publisher per sensor handle
// of a read-only sensor interface, on <robot ns>/<sensor name>, at
// publish_rate (required, Hz; 0 never publishes; a negative rate is
// refused), in the first update after starting and then once per
// 1/publish_rate of control time. Claims nothing.
//
// A controller derives from it with the interface and message type and
// says what a sensor's message starts as (prototype, non-real-time), how a
// reading fills it (fill, real-time, no allocation) and what it calls the
// sensors in messages (kind).
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/controllers/common/controller_params.hpp"
#include "servoloop/controllers/common/periodic_gate.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/realtime/realtime_publisher.hpp"
#include "servoloop/realtime/topic_bus.hpp"

namespace servoloop::controllers {

template <class Interface, class Msg>
class SensorPublishingController : public controller_manager::Controller<Interface> {
 public:
  using Handle = typename Interface::Handle;

  // Non-real-time. Throws servoloop::ConfigError for a missing or negative
  // publish_rate, or a sensor whose name is no topic name.
  bool init(Interface* hw, const controller_manager::ControllerContext& context) override {
    const double rate = requirePublishRate(context);
    gate_.setRate(rate);
    names_ = hw->getNames();
    std::sort(names_.begin(), names_.end());
    topics_.clear();
    sensors_.clear();
    sensors_.reserve(names_.size());
    for (const std::string& name : names_) {
      topics_.push_back(sensorTopic(context, name));
      Sensor& sensor = sensors_.emplace_back();
      sensor.handle = hw->getHandle(name);
      if (context.topics == nullptr) continue;
      const Msg prototype = prototypeOf(sensor.handle);
      sensor.publisher = context.topics->template advertise<Msg>(topics_.back(), prototype);
      sensor.publisher.msg() = prototype;
    }
    if (names_.empty()) {
      logger().warn("controller '{}': the hardware's {} has no sensor; nothing to publish", context.name,
                    hw->name());
    }
    if (rate == 0.0) {
      logger().warn("controller '{}': publish_rate 0, so the {} readings are never published (as in "
                    "ros_controllers); give a rate in Hz, e.g. publish_rate: 50",
                    context.name, kind());
    }
    return true;
  }

  // Real-time: the next update publishes.
  void starting(const Time& /*time*/) override { gate_.reset(); }

  // Real-time: publishes every sensor when due; allocates nothing.
  ReturnType update(const Time& time, const Duration& period) override {
    if (!gate_.due(time, period)) return ReturnType::ok;
    for (Sensor& sensor : sensors_) {
      // Not advertised (no bus), or the staging message is busy (another
      // thread inspecting it): this sensor skips this publication, as
      // realtime_tools does.
      if (!sensor.publisher.trylock()) continue;
      Msg& msg = sensor.publisher.msg();
      msg.stamp = time.seconds;
      fill(sensor.handle, msg);
      sensor.publisher.unlockAndPublish();
    }
    return ReturnType::ok;
  }

  // Non-real-time (after init): the published sensors, sorted by name, and
  // their topics in the same order.
  const std::vector<std::string>& sensorNames() const noexcept { return names_; }
  const std::vector<std::string>& topics() const noexcept { return topics_; }
  double publishRate() const noexcept { return gate_.rate(); }
  // Messages handed to the bus so far, all sensors together.
  std::uint64_t publishedCount() const noexcept {
    std::uint64_t count = 0;
    for (const Sensor& sensor : sensors_) count += sensor.publisher.publishedCount();
    return count;
  }

 protected:
  // Non-real-time: a sensor's message before its first reading.
  virtual Msg prototypeOf(const Handle& handle) const = 0;
  // Real-time: the reading into the message (its stamp is set).
  virtual void fill(const Handle& handle, Msg& msg) const noexcept = 0;
  // The sensors' kind in messages, e.g. "IMU".
  virtual const char* kind() const noexcept = 0;

 private:
  struct Sensor {
    Handle handle;
    realtime::RealtimePublisher<Msg> publisher;
  };

  // <robot ns>/<sensor>, with an error naming the sensor when its name
  // cannot be a topic name.
  std::string sensorTopic(const controller_manager::ControllerContext& context, const std::string& sensor) const {
    try {
      return namespaceTopic(context, sensor);
    } catch (const Error& e) {
      throw ConfigError("controller '" + context.name + "': " + kind() + " sensor '" + sensor +
                        "' cannot be a topic name (" + e.what() + "); rename the sensor in the hardware description");
    }
  }

  std::vector<Sensor> sensors_;  // sorted by name
  std::vector<std::string> names_;
  std::vector<std::string> topics_;
  PeriodicGate gate_;
};

}  // namespace servoloop::controllers
