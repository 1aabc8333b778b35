#pragma once
// effort_controllers/JointPositionController: drives one joint to a position
// setpoint with a PID on the position error, writing the joint effort — the
// controller of the seed's one_dof_ctl_params.yaml.
//
// Parameters (under <robot ns>/<controller>):
//   joint  required, the joint to drive (claimed on EffortJointInterface)
//   pid    required map, control_toolbox keys: p (required), i, d,
//          i_clamp / i_clamp_min / i_clamp_max, antiwindup
// Topics:
//   <robot ns>/<controller>/command  std_msgs/Float64 in, joint position setpoint (rad or m)
//   <robot ns>/<controller>/state    control_msgs/JointControllerState out, every 10th update
// Each update: the setpoint is clamped to the URDF position limits (revolute
// and prismatic joints); the error is the shortest angular distance that stays
// inside the limits (revolute), the shortest angular distance (continuous) or
// the difference (prismatic); effort = PID(error, period) — with the error's
// derivative from the PID, or from the velocity target when one was given
// through setCommand(position, velocity).
// Starting: setpoint = current position (clamped), PID reset.
#include <cstdint>

#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/realtime/realtime_buffer.hpp"
#include "servoloop/controllers/common/command_input.hpp"
#include "servoloop/controllers/common/controller_state_publisher.hpp"
#include "servoloop/controllers/common/joint_position_error.hpp"
#include "servoloop/controllers/pid.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"

namespace servoloop::controllers::effort_controllers {

class JointPositionController
    : public controller_manager::Controller<hardware_interface::EffortJointInterface> {
 public:
  // Non-real-time. Throws servoloop::ConfigError for a missing joint or pid
  // parameter, a joint the hardware or the URDF lacks.
  bool init(hardware_interface::EffortJointInterface* hw,
            const controller_manager::ControllerContext& context) override;
  // Real-time.
  void starting(const Time& time) override;
  // Real-time.
  ReturnType update(const Time& time, const Duration& period) override;

  // Any thread: a setpoint taken at the next update, in place of the topic's.
  // With velocity, the PID's derivative term uses velocity - joint velocity
  // instead of differentiating the error. Non-finite values are ignored.
  void setCommand(double position);
  void setCommand(double position, double velocity);

  // Any thread: the PID's gains (setGains takes effect at the next update).
  Pid& pid() noexcept { return pid_; }
  // Non-real-time: the PID, as "pid" (ros_control's <controller>/pid).
  std::vector<controller_manager::TunablePid> tunablePids() override { return {{"pid", &pid_}}; }

  // Controller thread, or once it stopped (diagnostics and tests).
  double setpoint() const noexcept { return setpoint_; }
  double effortCommand() const noexcept { return effort_; }
  const JointPositionError& positionError() const noexcept { return position_error_; }
  std::uint64_t rejectedNonFiniteCommands() const noexcept { return command_input_.rejectedNonFinite(); }

 private:
  struct Command {
    double position = 0.0;
    double velocity = 0.0;
    bool has_velocity = false;
  };

  // Real-time, out of the every-cycle path: a new setpoint (clamped to the
  // position limits) from the topic or setCommand(); the state message.
  [[gnu::noinline]] void takeNewSetpoint() noexcept;
  [[gnu::noinline]] void publishState(const Time& time, double position, double velocity, double error,
                                      double dt) noexcept;

  // In the order update() reads them, so that its data sits on few cache lines.
  hardware_interface::JointHandle joint_;
  JointPositionError position_error_;
  // Controller-thread state.
  double setpoint_ = 0.0;  // clamped to the position limits
  double velocity_target_ = 0.0;
  bool has_velocity_target_ = false;
  double effort_ = 0.0;
  Pid pid_;
  ControllerStatePublisher state_publisher_;
  ScalarCommandInput command_input_;
  servoloop::realtime::RealtimeBuffer<Command> direct_command_;  // from setCommand()
};

}  // namespace servoloop::controllers::effort_controllers
