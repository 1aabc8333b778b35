// The sensor handles and interfaces, compiled once here (their headers
// declare the ResourceManager instantiations extern).
#include <utility>

#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/contact_sensor_interface.hpp"
#include "servoloop/hardware_interface/force_torque_sensor_interface.hpp"
#include "servoloop/hardware_interface/imu_sensor_interface.hpp"

namespace servoloop::hardware_interface {

ImuSensorHandle::ImuSensorHandle(const Data& data) : data_(data) {
  if (data_.name.empty()) throw Error("IMU sensor handle: the name is empty");
}

ForceTorqueSensorHandle::ForceTorqueSensorHandle(std::string name, std::string frame_id, const double* force,
                                                 const double* torque)
    : name_(std::move(name)), frame_id_(std::move(frame_id)), force_(force), torque_(torque) {
  if (name_.empty()) throw Error("force-torque sensor handle: the name is empty");
  if (force == nullptr || torque == nullptr) {
    throw Error("force-torque sensor handle '" + name_ + "': force or torque data pointer is null");
  }
}

ContactSensorHandle::ContactSensorHandle(const Data& data) : data_(data) {
  if (data_.name.empty()) throw Error("contact sensor handle: the name is empty");
  if (data_.reading == nullptr) throw Error("contact sensor handle '" + data_.name + "': the reading pointer is null");
}

template class ResourceManager<ImuSensorHandle, false>;
template class ResourceManager<ContactSensorHandle, false>;
template class ResourceManager<ForceTorqueSensorHandle, false>;

const char* ImuSensorInterface::name() const { return "ImuSensorInterface"; }
const char* ForceTorqueSensorInterface::name() const { return "ForceTorqueSensorInterface"; }
const char* ContactSensorInterface::name() const { return "ContactSensorInterface"; }

}  // namespace servoloop::hardware_interface
