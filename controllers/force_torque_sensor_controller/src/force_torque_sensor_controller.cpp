#include "servoloop/controllers/force_torque_sensor_controller/force_torque_sensor_controller.hpp"

#include <algorithm>

#include "servoloop/controllers/common/controller_params.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/plugin/plugin_register.hpp"
#include "servoloop/realtime/topic_bus.hpp"

namespace servoloop::controllers {

namespace cm = controller_manager;
namespace hi = hardware_interface;
using WrenchMsg = servoloop::geometry_msgs::WrenchStamped;

namespace {

// <robot ns>/<sensor>, with an error naming the sensor when its name cannot
// be a topic name.
std::string sensorTopic(const cm::ControllerContext& context, const std::string& sensor) {
  try {
    return namespaceTopic(context, sensor);
  } catch (const Error& e) {
    throw ConfigError("controller '" + context.name + "': force-torque sensor '" + sensor +
                      "' cannot be a topic name (" + e.what() + "); rename the sensor in the hardware description");
  }
}

}  // namespace

bool ForceTorqueSensorController::init(hi::ForceTorqueSensorInterface* hw, const cm::ControllerContext& context) {
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
    WrenchMsg prototype;
    prototype.frame_id = sensor.handle.getFrameId();
    sensor.publisher = context.topics->advertise<WrenchMsg>(topics_.back(), prototype);
    sensor.publisher.msg() = prototype;
  }
  if (names_.empty()) {
    logger().warn("controller '{}': the hardware's ForceTorqueSensorInterface has no sensor; nothing to publish",
                  context.name);
  }
  if (rate == 0.0) {
    logger().warn("controller '{}': publish_rate 0, so wrenches are never published (as in ros_controllers); "
                  "give a rate in Hz, e.g. publish_rate: 50",
                  context.name);
  }
  return true;
}

std::uint64_t ForceTorqueSensorController::publishedCount() const noexcept {
  std::uint64_t count = 0;
  for (const Sensor& sensor : sensors_) count += sensor.publisher.publishedCount();
  return count;
}

void ForceTorqueSensorController::starting(const Time& /*time*/) { gate_.reset(); }

ReturnType ForceTorqueSensorController::update(const Time& time, const Duration& period) {
  if (!gate_.due(time, period)) return ReturnType::ok;
  for (Sensor& sensor : sensors_) {
    // Not advertised (no bus), or the staging message is busy (another thread
    // inspecting it): this sensor skips this publication, as realtime_tools does.
    if (!sensor.publisher.trylock()) continue;
    WrenchMsg& msg = sensor.publisher.msg();
    // A registered handle's pointers are never null (its constructor refuses them).
    const double* force = sensor.handle.getForce();
    const double* torque = sensor.handle.getTorque();
    msg.stamp = time.seconds;
    msg.wrench.force = {force[0], force[1], force[2]};
    msg.wrench.torque = {torque[0], torque[1], torque[2]};
    sensor.publisher.unlockAndPublish();
  }
  return ReturnType::ok;
}

}  // namespace servoloop::controllers

SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::ForceTorqueSensorController,
                          servoloop::controller_manager::ControllerBase,
                          "force_torque_sensor_controller/ForceTorqueSensorController")
