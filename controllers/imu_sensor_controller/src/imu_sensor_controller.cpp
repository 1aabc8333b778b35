#include "servoloop/controllers/imu_sensor_controller/imu_sensor_controller.hpp"

#include <algorithm>
#include <array>

#include "servoloop/plugin/plugin_register.hpp"

namespace servoloop::controllers {

namespace hi = hardware_interface;
using ImuMsg = servoloop::sensor_msgs::Imu;

namespace {

// Real-time: a measured covariance (9 values, row-major); none given stays all
// zero, ROS's "unknown".
void copyCovariance(const double* covariance, std::array<double, 9>& out) noexcept {
  if (covariance != nullptr) std::copy(covariance, covariance + 9, out.begin());
}

}  // namespace

// Its frame, and what the sensor does not measure already in its published
// form (zero, covariance[0] = -1), so fill() writes only the measured values.
ImuMsg ImuSensorController::prototypeOf(const hi::ImuSensorHandle& handle) const {
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

void ImuSensorController::fill(const hi::ImuSensorHandle& imu, ImuMsg& msg) const noexcept {
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
}

}  // namespace servoloop::controllers

SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::ImuSensorController,
                          servoloop::controller_manager::ControllerBase,
                          "imu_sensor_controller/ImuSensorController")
