#include "servoloop/controllers/force_torque_sensor_controller/force_torque_sensor_controller.hpp"

#include "servoloop/plugin/plugin_register.hpp"

namespace servoloop::controllers {

namespace hi = hardware_interface;
using WrenchMsg = servoloop::geometry_msgs::WrenchStamped;

WrenchMsg ForceTorqueSensorController::prototypeOf(const hi::ForceTorqueSensorHandle& handle) const {
  WrenchMsg msg;
  msg.frame_id = handle.getFrameId();
  return msg;
}

void ForceTorqueSensorController::fill(const hi::ForceTorqueSensorHandle& sensor, WrenchMsg& msg) const noexcept {
  // A registered handle's pointers are never null (its constructor refuses them).
  const double* force = sensor.getForce();
  const double* torque = sensor.getTorque();
  msg.wrench.force = {force[0], force[1], force[2]};
  msg.wrench.torque = {torque[0], torque[1], torque[2]};
}

}  // namespace servoloop::controllers

SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::ForceTorqueSensorController,
                          servoloop::controller_manager::ControllerBase,
                          "force_torque_sensor_controller/ForceTorqueSensorController")
