#pragma once
// An inertial measurement unit, as ros_control's ImuSensorHandle gives it:
// the sensor frame's orientation, angular velocity and specific force
// (linear acceleration with gravity: +9.81 m/s² upwards at rest), each with
// its 3×3 row-major covariance. Pointers into storage the RobotHW owns and
// updates in read(); a null pointer: the sensor does not measure that.
// Reading is real-time safe.
#include <string>

#include "servoloop/hardware_interface/resource_manager.hpp"

namespace servoloop::hardware_interface {

class ImuSensorHandle {
 public:
  struct Data {
    std::string name;      // the sensor's name: handle and topic name
    std::string frame_id;  // the frame the data is given in
    const double* orientation = nullptr;                     // quaternion x, y, z, w: sensor -> reference
    const double* orientation_covariance = nullptr;          // 9, rad²
    const double* angular_velocity = nullptr;                // 3, rad/s, sensor axes
    const double* angular_velocity_covariance = nullptr;     // 9, (rad/s)²
    const double* linear_acceleration = nullptr;             // 3, m/s², sensor axes
    const double* linear_acceleration_covariance = nullptr;  // 9, (m/s²)²
  };

  ImuSensorHandle() = default;
  // Throws servoloop::Error for an empty name.
  explicit ImuSensorHandle(const Data& data);

  const std::string& getName() const { return data_.name; }
  const std::string& getFrameId() const { return data_.frame_id; }
  const double* getOrientation() const { return data_.orientation; }
  const double* getOrientationCovariance() const { return data_.orientation_covariance; }
  const double* getAngularVelocity() const { return data_.angular_velocity; }
  const double* getAngularVelocityCovariance() const { return data_.angular_velocity_covariance; }
  const double* getLinearAcceleration() const { return data_.linear_acceleration; }
  const double* getLinearAccelerationCovariance() const { return data_.linear_acceleration_covariance; }

 private:
  Data data_;
};

extern template class ResourceManager<ImuSensorHandle, false>;

// Read-only: claims nothing, any number of controllers may read a sensor.
class ImuSensorInterface : public ResourceManager<ImuSensorHandle, false> {
 public:
  const char* name() const override;
};

}  // namespace servoloop::hardware_interface
