#pragma once
// imu_sensor_controller/ImuSensorController: publishes every IMU of the
// hardware, as ros_controllers' imu_sensor_controller does.
//
// Parameters (under <robot ns>/<controller>):
//   publish_rate  required, Hz; 0 never publishes (as in ros_controllers),
//                 a negative rate is refused
// Topics: <robot ns>/<sensor name>, sensor_msgs/Imu, one per sensor handle of
// the ImuSensorInterface (e.g. /robot/imu for a sensor named "imu"), frame_id
// the handle's frame. Published in the first update after starting, then once
// per 1/publish_rate of control time. A value the sensor does not give (a
// null pointer in its handle) is published as zero with element 0 of its
// covariance -1, ROS's "not measured"; a covariance it does not give is all
// zero, ROS's "unknown". Reads sensors only: claims nothing.
#include "servoloop/controllers/common/sensor_publishing_controller.hpp"
#include "servoloop/hardware_interface/imu_sensor_interface.hpp"
#include "servoloop/realtime/messages.hpp"

namespace servoloop::controllers {

class ImuSensorController final
    : public SensorPublishingController<hardware_interface::ImuSensorInterface, servoloop::sensor_msgs::Imu> {
 protected:
  servoloop::sensor_msgs::Imu prototypeOf(const hardware_interface::ImuSensorHandle& handle) const override;
  void fill(const hardware_interface::ImuSensorHandle& imu, servoloop::sensor_msgs::Imu& msg) const noexcept override;
  const char* kind() const noexcept override { return "IMU"; }
};

}  // namespace servoloop::controllers
