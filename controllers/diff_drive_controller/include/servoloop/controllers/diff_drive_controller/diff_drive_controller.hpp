#pragma once
// diff_drive_controller/DiffDriveController: drives a differential-drive base
// from velocity commands and reports its odometry, as ros_controllers'
// controller of that name does, with its parameters.
//
// Parameters (under <robot ns>/<controller>):
//   left_wheel, right_wheel           a wheel joint name or a list (same count per side),
//                                     claimed on VelocityJointInterface
//   wheel_separation, wheel_radius    m; from the URDF when not given (wheel_geometry.hpp)
//   wheel_separation_multiplier       1.0
//   left_wheel_radius_multiplier,     1.0 each (wheel_radius_multiplier sets both)
//   right_wheel_radius_multiplier
//   cmd_vel_timeout                   0.5 s: with no command for longer, the base stops;
//                                     the first timeout is logged, each one published on
//                                     <robot ns>/<controller>/command_timed_out
//   linear/x/..., angular/z/...       velocity, acceleration and jerk limits (speed_limiter.hpp)
//   publish_rate                      50 Hz of odom and tf
//   velocity_rolling_window_size      10 updates averaged for the odometry's velocities;
//                                     a whole number from 1 to kMaxVelocityWindow (1000)
//   open_loop                         false: odometry from the wheels; true: from the commands
//   pose_covariance_diagonal,         6 values each (x, y, z, roll, pitch, yaw), default 0
//   twist_covariance_diagonal
//   base_frame_id, odom_frame_id      "base_link", "odom"
//   enable_odom_tf                    true: also publish odom → base_link on /tf
// Topics:
//   <robot ns>/<controller>/cmd_vel   geometry_msgs/Twist in (linear.x, angular.z used)
//   <robot ns>/<controller>/odom      nav_msgs/Odometry out
//   /tf                               tf2_msgs/TFMessage out (odom → base)
// Each update: the odometry integrates the wheels' rotation since the last
// update; the newest command (zeroed after cmd_vel_timeout) is limited and
// turned into wheel speeds, left = (v − ω·s/2)/r_left, right = (v + ω·s/2)/r_right.
// Non-finite commands are ignored (the previous one stays) and counted.
// Starting: the base is braked and the odometry starts at the origin.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/controllers/common/command_timeout.hpp"
#include "servoloop/controllers/common/periodic_gate.hpp"
#include "servoloop/controllers/diff_drive_controller/odometry.hpp"
#include "servoloop/controllers/diff_drive_controller/speed_limiter.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/realtime/messages.hpp"
#include "servoloop/realtime/realtime_publisher.hpp"
#include "servoloop/realtime/realtime_subscriber.hpp"
#include "servoloop/realtime/topic_subscription.hpp"

namespace servoloop::controllers::diff_drive_controller {

class DiffDriveController : public controller_manager::Controller<hardware_interface::VelocityJointInterface> {
 public:
  // velocity_rolling_window_size: ros_controllers' default, and the largest
  // taken (the samples are allocated at load and summed every update).
  static constexpr std::size_t kDefaultVelocityWindow = 10;
  static constexpr std::size_t kMaxVelocityWindow = 1000;

  // Non-real-time. Throws servoloop::ConfigError naming the parameter.
  bool init(hardware_interface::VelocityJointInterface* hw,
            const controller_manager::ControllerContext& context) override;
  // Real-time.
  void starting(const Time& time) override;
  void stopping(const Time& time) override;
  ReturnType update(const Time& time, const Duration& period) override;

  const Odometry& odometry() const noexcept { return odometry_; }
  double wheelSeparation() const noexcept { return wheel_separation_; }
  double wheelRadius() const noexcept { return wheel_radius_; }
  std::uint64_t rejectedCommands() const noexcept { return rejected_->load(std::memory_order_relaxed); }

 private:
  struct Command {
    double linear = 0.0;
    double angular = 0.0;
    double stamp = 0.0;  // control time it was taken
  };
  void brake() noexcept;
  [[gnu::noinline]] void publishOdometry(const Time& time) noexcept;

  std::vector<hardware_interface::JointHandle> left_wheels_, right_wheels_;
  double wheel_separation_ = 0.0;
  double wheel_radius_ = 0.0;
  double separation_multiplier_ = 1.0;
  double left_radius_multiplier_ = 1.0;
  double right_radius_multiplier_ = 1.0;
  double cmd_vel_timeout_ = 0.5;
  bool open_loop_ = false;
  bool publish_tf_ = true;
  SpeedLimiter linear_limiter_, angular_limiter_;
  PeriodicGate publish_gate_;

  servoloop::realtime::RealtimeSubscriber<servoloop::geometry_msgs::Twist> command_input_;
  servoloop::realtime::Subscription command_checker_;  // logs the first bad command, off the real-time thread
  std::shared_ptr<std::atomic<std::uint64_t>> rejected_ = std::make_shared<std::atomic<std::uint64_t>>(0);
  servoloop::realtime::RealtimePublisher<servoloop::nav_msgs::Odometry> odom_publisher_;
  servoloop::realtime::RealtimePublisher<servoloop::tf2_msgs::TFMessage> tf_publisher_;

  // Controller-thread state.
  Odometry odometry_;
  Command command_;              // the newest usable command
  CommandTimeout timeout_;       // reports cmd_vel_timeout (the zeroing is update()'s)
  Command last0_, last1_;        // the limited commands of the last two cycles
};

}  // namespace servoloop::controllers::diff_drive_controller
