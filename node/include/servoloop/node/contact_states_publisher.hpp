#pragma once
// What gazebo_ros_bumper publishes for each contact sensor of a simulated
// robot: gazebo_msgs/ContactsState on <namespace>/<bumperTopicName> (the
// sensor's name without a plugin), at the sensor's update rate (every
// control cycle without one), one ContactState per other collision with
// each contact point's wrench on the sensor's collision (the torque about
// the sensor link's origin), position, normal and depth, and their sum.
// As in gazebo_ros_bumper the values are in the world frame, whatever
// frame_id (frameName, default "world") says.
//
// The messages are built and published between the world's segments of
// cycles, off the real-time path (their size changes with the contacts);
// the sensor's reading is the one of the segment's last cycle.
#include <cstdint>
#include <string>
#include <vector>

#include "servoloop/hardware_interface/contact_sensor_interface.hpp"
#include "servoloop/realtime/messages.hpp"
#include "servoloop/realtime/topic_bus.hpp"

namespace servoloop::node {

class ContactStatesPublisher {
 public:
  // Non-real-time. One topic per handle of `sensors`, resolved in
  // `robot_namespace`. `time_step_s` is the physics step; `steps_per_cycle`
  // the steps of one control cycle (the rate of sensors without one).
  // `sensors` and `bus` must outlive it.
  ContactStatesPublisher(hardware_interface::ContactSensorInterface& sensors, realtime::TopicBus& bus,
                         const std::string& robot_namespace, double time_step_s, std::uint64_t steps_per_cycle);

  // Between two segments, `steps_taken` steps since the start: publishes
  // each sensor that is due; returns the steps until the next is due (>= 1).
  std::uint64_t publishDue(std::uint64_t steps_taken);
  // The world was reset: every sensor is due at once.
  void restart() noexcept;

  // Non-real-time: the topics, in the handles' order.
  std::vector<std::string> topics() const;

  // The message of one reading (for publishDue, and tests).
  static gazebo_msgs::ContactsState message(const hardware_interface::ContactSensorHandle& sensor, double stamp_s);

 private:
  struct Sensor {
    hardware_interface::ContactSensorHandle handle;
    std::string topic;
    std::uint64_t steps_per_message = 1;
    std::uint64_t next_step = 0;
  };
  realtime::TopicBus& bus_;
  double time_step_s_;
  std::uint64_t last_steps_ = 0;
  std::vector<Sensor> sensors_;
};

}  // namespace servoloop::node
