#pragma once
// effort_controllers/JointVelocityController: drives one joint to a velocity
// setpoint with a PID on the velocity error, writing the joint effort.
//
// Parameters (under <robot ns>/<controller>):
//   joint  required, the joint to drive (claimed on EffortJointInterface)
//   pid    required map, control_toolbox keys: p (required), i, d,
//          i_clamp / i_clamp_min / i_clamp_max, antiwindup
// Topics:
//   <robot ns>/<controller>/command  std_msgs/Float64 in, joint velocity setpoint (rad/s or m/s)
//   <robot ns>/<controller>/state    control_msgs/JointControllerState out, every 10th update
//                                    (set_point and process_value are velocities;
//                                    process_value_dot is not measured and stays 0)
// Each update: error = v_cmd - v; effort = PID(error, period).
// Starting: v_cmd = 0, PID reset.
#include <cstdint>

#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/controllers/common/command_input.hpp"
#include "servoloop/controllers/common/controller_state_publisher.hpp"
#include "servoloop/controllers/pid.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"

namespace servoloop::controllers::effort_controllers {

class JointVelocityController
    : public controller_manager::Controller<hardware_interface::EffortJointInterface> {
 public:
  // Non-real-time. Throws servoloop::ConfigError for a missing joint or pid parameter.
  bool init(hardware_interface::EffortJointInterface* hw,
            const controller_manager::ControllerContext& context) override;
  // Real-time.
  void starting(const Time& time) override;
  // Real-time.
  ReturnType update(const Time& time, const Duration& period) override;

  // Any thread: the PID's gains (setGains takes effect at the next update).
  Pid& pid() noexcept { return pid_; }
  // Non-real-time: the PID, as "pid" (ros_control's <controller>/pid).
  std::vector<controller_manager::TunablePid> tunablePids() override { return {{"pid", &pid_}}; }

  // Controller thread, or once it stopped (diagnostics and tests).
  double velocitySetpoint() const noexcept { return velocity_setpoint_; }
  double effortCommand() const noexcept { return effort_; }
  std::uint64_t rejectedNonFiniteCommands() const noexcept { return command_input_.rejectedNonFinite(); }

 private:
  hardware_interface::JointHandle joint_;
  Pid pid_;
  ScalarCommandInput command_input_;
  ControllerStatePublisher state_publisher_;

  double velocity_setpoint_ = 0.0;
  double effort_ = 0.0;
};

}  // namespace servoloop::controllers::effort_controllers
