#include "servoloop/controllers/imu_sensor_controller/imu_sensor_controller.hpp"

#include <algorithm>
#include <array>

#include "servoloop/controllers/common/controller_params.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/plugin/plugin_register.hpp"
#include "servoloop/realtime/topic_bus.hpp"

namespace servoloop::controllers {

namespace cm = controller_manager;
namespace hi = hardware_interface;
using ImuMsg = servoloop::sensor_msgs::Imu;

namespace {

// <robot ns>/<sensor>, with an error naming the sensor when its name cannot
// be a topic name.
std::string sensorTopic(const cm::ControllerContext& context, const std::string& sensor) {
  try {
    return namespaceTopic(context, sensor);
  } catch (const Error& e) {
    throw ConfigError("controller '" + context.name + "': IMU sensor '" + sensor +
                      "' cannot be a topic name (" + e.what() + "); rename the sensor in the hardware description");
  }
}

// One sensor's message as init prepares it: its frame, and what the sensor
// does not measure already in its published form (zero, covariance[0] = -1),
// so update() writes only the measured values.
ImuMsg prototypeFor(const hi::ImuSensorHandle& handle) {
  ImuMsg msg;
  msg.frame_id = handle.getFrameId();
  if (handle.getOrientation() == nullptr) {
    msg.orientation = {0.0, 0.0, 0.0, 0.0};
    msg.orientation_covariance[0] = -1.0;
  }
  if (handle.getAngularVelocity() == nullptr) msg.angular_velocity_covariance[0] = -1.0;
  if (handle.getLinearAcceleration() == nullptr) msg.linear_acceleration_covariance[0] = -1.0;
  return msg;
}

// Real-time: a measured covariance (9 values, row-major); none given stays all
// zero, ROS's "unknown".
void copyCovariance(const double* covariance, std::array<double, 9>& out) noexcept {
  if (covariance != nullptr) std::copy(covariance, covariance + 9, out.begin());
}

}  // namespace

bool ImuSensorController::init(hi::ImuSensorInterface* hw, const cm::ControllerContext& context) {
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
    const ImuMsg prototype = prototypeFor(sensor.handle);
    sensor.publisher = context.topics->advertise<ImuMsg>(topics_.back(), prototype);
    sensor.publisher.msg() = prototype;
  }
  if (names_.empty()) {
    logger().warn("controller '{}': the hardware's ImuSensorInterface has no sensor; nothing to publish", context.name);
  }
  if (rate == 0.0) {
    logger().warn("controller '{}': publish_rate 0, so IMU readings are never published (as in ros_controllers); "
                  "give a rate in Hz, e.g. publish_rate: 50",
                  context.name);
  }
  return true;
}

std::uint64_t ImuSensorController::publishedCount() const noexcept {
  std::uint64_t count = 0;
  for (const Sensor& sensor : sensors_) count += sensor.publisher.publishedCount();
  return count;
}

void ImuSensorController::starting(const Time& /*time*/) { gate_.reset(); }

ReturnType ImuSensorController::update(const Time& time, const Duration& period) {
  if (!gate_.due(time, period)) return ReturnType::ok;
  for (Sensor& sensor : sensors_) {
    // Not advertised (no bus), or the staging message is busy (another thread
    // inspecting it): this sensor skips this publication, as realtime_tools does.
    if (!sensor.publisher.trylock()) continue;
    ImuMsg& msg = sensor.publisher.msg();
    const hi::ImuSensorHandle& imu = sensor.handle;
    msg.stamp = time.seconds;
    if (const double* q = imu.getOrientation()) {
      msg.orientation = {q[0], q[1], q[2], q[3]};
      copyCovariance(imu.getOrientationCovariance(), msg.orientation_covariance);
    }
    if (const double* w = imu.getAngularVelocity()) {
      msg.angular_velocity = {w[0], w[1], w[2]};
      copyCovariance(imu.getAngularVelocityCovariance(), msg.angular_velocity_covariance);
    }
    if (const double* a = imu.getLinearAcceleration()) {
      msg.linear_acceleration = {a[0], a[1], a[2]};
      copyCovariance(imu.getLinearAccelerationCovariance(), msg.linear_acceleration_covariance);
    }
    sensor.publisher.unlockAndPublish();
  }
  return ReturnType::ok;
}

}  // namespace servoloop::controllers

SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::ImuSensorController,
                          servoloop::controller_manager::ControllerBase,
                          "imu_sensor_controller/ImuSensorController")
