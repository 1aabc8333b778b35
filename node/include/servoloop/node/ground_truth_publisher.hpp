#pragma once
// Ground truth of a floating robot's base, as Gazebo's p3d plugin gives it:
// nav_msgs/Odometry on <namespace>/ground_truth/odom, the root link's pose in
// the world frame and its twist in the root link's own axes, from the
// simulator's state. Published from the loop thread, after a control update,
// at a fixed rate of control time.
#include <string>

#include "servoloop/controller_manager/control_loop.hpp"
#include "servoloop/hardware_interface/simulated_robot_hw.hpp"
#include "servoloop/realtime/messages.hpp"
#include "servoloop/realtime/realtime_publisher.hpp"
#include "servoloop/realtime/topic_bus.hpp"

namespace servoloop::node {

class GroundTruthPublisher final : public controller_manager::LoopCycleHook {
 public:
  static constexpr double kDefaultRateHz = 50.0;

  // Non-real-time. True when `hardware` reports a floating base.
  static bool applies(const hardware_interface::SimulatedRobotHW& hardware);

  // Non-real-time. Advertises `topic` (nav_msgs/Odometry) on `bus`;
  // `root_link` names the child frame. `hardware` and `bus` must outlive it.
  GroundTruthPublisher(const hardware_interface::SimulatedRobotHW& hardware, realtime::TopicBus& bus,
                       const std::string& topic, const std::string& root_link, double rate_hz = kDefaultRateHz);

  // Real-time: publishes when 1/rate of control time has passed since the
  // last message (and at the first update). No allocation, lock or throw.
  void afterUpdate(const Time& time, const Duration& period) noexcept override;
  // Non-real-time, no cycle running: time starts again (the next update publishes).
  void restart() noexcept { next_time_s_ = -1e300; }

 private:
  const hardware_interface::SimulatedRobotHW& hardware_;
  realtime::RealtimePublisher<nav_msgs::Odometry> publisher_;
  double interval_s_;
  double next_time_s_ = -1e300;
};

}  // namespace servoloop::node
