#pragma once
// my_controllers/GravityCompensatedPD: holds one revolute joint at a commanded
// position with a PD law plus a feed-forward term that cancels the gravity
// torque of a single link (a pendulum), all in joint space:
//
//   effort = kp·(q_cmd − q) − kd·q̇ − gravity_torque·sin(q − upright_position)
//
// clamped to ±max_effort. gravity_torque is m·g·l of the link (N·m: mass times
// gravity times the distance from the joint axis to the link's centre of mass);
// upright_position is the joint position at which that centre of mass is
// straight above the axis. Gravity then pulls with +gravity_torque·sin(q − q_up)
// about the axis, and the controller pushes back with the same amount.
//
// Parameters (the controller's YAML node):
//   joint             required   joint to drive, through EffortJointInterface
//   kp                required   N·m/rad
//   kd                optional   N·m·s/rad, default 0
//   gravity_torque    optional   N·m, default 0 (plain PD)
//   upright_position  optional   rad, default 0
//   max_effort        optional   N·m, default: no clamp
// Topic: <robot ns>/<controller name>/command, std_msgs/Float64, the joint
// position to hold (rad). Until the first command, it holds the position the
// joint had when the controller started.
#include <limits>
#include <string>

#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/realtime/messages.hpp"
#include "servoloop/realtime/realtime_subscriber.hpp"
#include "servoloop/hardware_interface/joint_handle.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"

namespace my_controllers {

class GravityCompensatedPDController
    : public servoloop::controller_manager::Controller<servoloop::hardware_interface::EffortJointInterface> {
 public:
  // Non-real-time: reads the parameters, claims the joint, connects the command topic.
  bool init(servoloop::hardware_interface::EffortJointInterface* hw,
            const servoloop::controller_manager::ControllerContext& context) override;

  // Real-time: hold the current position until a command arrives.
  void starting(const servoloop::Time& time) override;

  // Real-time: one control step; no allocation, no lock, no throw.
  servoloop::ReturnType update(const servoloop::Time& time, const servoloop::Duration& period) override;

  // Real-time: forget the setpoint so a restart holds where the joint is then.
  void stopping(const servoloop::Time& time) override;

  // The command topic, e.g. "/one_DOF_robot/arm_pd/command" (set by init).
  const std::string& commandTopic() const { return command_topic_; }

 private:
  // Gains and model, fixed at init.
  double kp_ = 0.0;                // N·m/rad
  double kd_ = 0.0;                // N·m·s/rad
  double gravity_torque_ = 0.0;    // m·g·l, N·m
  double upright_position_ = 0.0;  // rad
  double max_effort_ = std::numeric_limits<double>::infinity();  // N·m

  servoloop::hardware_interface::JointHandle joint_;
  std::string command_topic_;
  servoloop::realtime::RealtimeSubscriber<servoloop::std_msgs::Float64> command_;

  // Joint position to hold (rad); only the real-time thread touches it.
  double position_setpoint_ = 0.0;
};

}  // namespace my_controllers
