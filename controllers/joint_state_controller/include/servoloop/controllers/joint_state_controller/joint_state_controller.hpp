#pragma once
// joint_state_controller/JointStateController: publishes the state of every
// joint the hardware has, as ros_control's joint_state_controller does.
//
// Parameters (under <robot ns>/<controller>):
//   publish_rate  required, Hz; 0 never publishes (as in ros_controllers),
//                 a negative rate is refused
//   extra_joints  optional list of {name, position, velocity, effort}:
//                 joints the hardware does not have, published with those
//                 constant values (each value defaults to 0)
// Topic: <robot ns>/joint_states, sensor_msgs/JointState: the hardware's
// joints sorted by name, then the extra joints in the order given. Published
// in the first update after starting, then once per 1/publish_rate of
// control time.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/realtime/messages.hpp"
#include "servoloop/realtime/realtime_publisher.hpp"
#include "servoloop/controllers/common/periodic_gate.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"

namespace servoloop::controllers {

class JointStateController
    : public controller_manager::Controller<hardware_interface::JointStateInterface> {
 public:
  // Non-real-time. Throws servoloop::ConfigError for a missing or malformed
  // publish_rate or extra_joints entry.
  bool init(hardware_interface::JointStateInterface* hw,
            const controller_manager::ControllerContext& context) override;

  // Real-time: the next update publishes.
  void starting(const Time& time) override;
  // Real-time: publishes when due.
  ReturnType update(const Time& time, const Duration& period) override;

  // Non-real-time (after init): the published joint names, in message order.
  const std::vector<std::string>& jointNames() const noexcept { return prototype_.name; }
  double publishRate() const noexcept { return gate_.rate(); }
  // Messages handed to the bus so far.
  std::uint64_t publishedCount() const noexcept { return publisher_.publishedCount(); }

 private:
  void readExtraJoints(const controller_manager::ControllerContext& context);

  std::vector<hardware_interface::JointStateHandle> joints_;  // sorted by name
  servoloop::sensor_msgs::JointState prototype_;     // names + extra joints' values
  servoloop::realtime::RealtimePublisher<servoloop::sensor_msgs::JointState> publisher_;
  PeriodicGate gate_;
};

}  // namespace servoloop::controllers
