#pragma once
// force_torque_sensor_controller/ForceTorqueSensorController: publishes every
// force-torque sensor of the hardware, as ros_controllers'
// force_torque_sensor_controller does.
//
// Parameters (under <robot ns>/<controller>):
//   publish_rate  required, Hz; 0 never publishes (as in ros_controllers),
//                 a negative rate is refused
// Topics: <robot ns>/<sensor name>, geometry_msgs/WrenchStamped, one per
// sensor handle of the ForceTorqueSensorInterface (e.g. /robot/wrist_ft for a
// sensor named "wrist_ft"): force (N) and torque (N·m) in the handle's frame,
// which is the message's frame_id. Published in the first update after
// starting, then once per 1/publish_rate of control time. Reads sensors only:
// claims nothing.
#include "servoloop/controllers/common/sensor_publishing_controller.hpp"
#include "servoloop/hardware_interface/force_torque_sensor_interface.hpp"
#include "servoloop/realtime/messages.hpp"

namespace servoloop::controllers {

class ForceTorqueSensorController final
    : public SensorPublishingController<hardware_interface::ForceTorqueSensorInterface,
                                        servoloop::geometry_msgs::WrenchStamped> {
 protected:
  servoloop::geometry_msgs::WrenchStamped prototypeOf(
      const hardware_interface::ForceTorqueSensorHandle& handle) const override;
  void fill(const hardware_interface::ForceTorqueSensorHandle& sensor,
            servoloop::geometry_msgs::WrenchStamped& msg) const noexcept override;
  const char* kind() const noexcept override { return "force-torque"; }
};

}  // namespace servoloop::controllers
