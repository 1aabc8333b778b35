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
#include <cstdint>
#include <string>
#include <vector>

#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/controllers/common/periodic_gate.hpp"
#include "servoloop/hardware_interface/force_torque_sensor_interface.hpp"
#include "servoloop/realtime/messages.hpp"
#include "servoloop/realtime/realtime_publisher.hpp"

namespace servoloop::controllers {

class ForceTorqueSensorController
    : public controller_manager::Controller<hardware_interface::ForceTorqueSensorInterface> {
 public:
  // Non-real-time. Throws servoloop::ConfigError for a missing or negative
  // publish_rate, or a sensor whose name is no topic name.
  bool init(hardware_interface::ForceTorqueSensorInterface* hw,
            const controller_manager::ControllerContext& context) override;

  // Real-time: the next update publishes.
  void starting(const Time& time) override;
  // Real-time: publishes every sensor when due; allocates nothing.
  ReturnType update(const Time& time, const Duration& period) override;

  // Non-real-time (after init): the published sensors, sorted by name, and
  // their topics in the same order.
  const std::vector<std::string>& sensorNames() const noexcept { return names_; }
  const std::vector<std::string>& topics() const noexcept { return topics_; }
  double publishRate() const noexcept { return gate_.rate(); }
  // Messages handed to the bus so far, all sensors together.
  std::uint64_t publishedCount() const noexcept;

 private:
  struct Sensor {
    hardware_interface::ForceTorqueSensorHandle handle;
    servoloop::realtime::RealtimePublisher<servoloop::geometry_msgs::WrenchStamped> publisher;
  };

  std::vector<Sensor> sensors_;  // sorted by name
  std::vector<std::string> names_;
  std::vector<std::string> topics_;
  PeriodicGate gate_;
};

}  // namespace servoloop::controllers
