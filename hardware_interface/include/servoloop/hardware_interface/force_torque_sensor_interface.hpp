#pragma once
// A six-axis force-torque sensor, as ros_control's ForceTorqueSensorHandle
// gives it: force (N) and torque (N·m) in the frame frame_id, the torque about
// that frame's origin. Pointers into storage the RobotHW owns and updates in
// read(). Reading is real-time safe.
#include <string>

#include "servoloop/hardware_interface/resource_manager.hpp"

namespace servoloop::hardware_interface {

class ForceTorqueSensorHandle {
 public:
  ForceTorqueSensorHandle() = default;
  // Throws servoloop::Error for an empty name or a null pointer.
  ForceTorqueSensorHandle(std::string name, std::string frame_id, const double* force, const double* torque);

  const std::string& getName() const { return name_; }
  const std::string& getFrameId() const { return frame_id_; }
  const double* getForce() const { return force_; }    // 3
  const double* getTorque() const { return torque_; }  // 3

 private:
  std::string name_;
  std::string frame_id_;
  const double* force_ = nullptr;
  const double* torque_ = nullptr;
};

extern template class ResourceManager<ForceTorqueSensorHandle, false>;

// Read-only: claims nothing.
class ForceTorqueSensorInterface : public ResourceManager<ForceTorqueSensorHandle, false> {
 public:
  const char* name() const override;
};

}  // namespace servoloop::hardware_interface
