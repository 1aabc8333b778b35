#pragma once
// minimal_joint_controller/MinimalJointController: the seed tutorial's raw PD
// joint controller ("minimal joint controller"), as a controller plugin with
// the seed's numbers as parameter defaults.
//
// Parameters (under <robot ns>/<controller>):
//   joint        default "joint1"   (claimed on EffortJointInterface)
//   kp           default 10  (N·m/rad)
//   kv           default 3   (N·m·s/rad)
//   update_rate  default 100 (Hz); the controller manager also honours it
// Topics:
//   <robot ns>/<controller>/pos_cmd  std_msgs/Float64 in, joint angle command (rad)
//   <robot ns>/<controller>/jnt_pos  std_msgs/Float64 out, measured joint angle
//   <robot ns>/<controller>/jnt_vel  std_msgs/Float64 out, measured joint velocity
//   <robot ns>/<controller>/jnt_trq  std_msgs/Float64 out, commanded joint effort
//   <robot ns>/joint_states          sensor_msgs/JointState out (name, position, velocity)
// At update_rate: effort = kp·wrap(cmd - q) - kv·q̇, wrap into (-π, π], and
// every topic is published once. The effort is written every cycle and held
// between those updates. Starting: cmd = 0 (as the seed's node starts).
#include <cstdint>

#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/realtime/messages.hpp"
#include "servoloop/realtime/realtime_publisher.hpp"
#include "servoloop/controllers/common/command_input.hpp"
#include "servoloop/controllers/common/periodic_gate.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"

namespace servoloop::controllers {

class MinimalJointController
    : public controller_manager::Controller<hardware_interface::EffortJointInterface> {
 public:
  static constexpr const char* kDefaultJoint = "joint1";
  static constexpr double kDefaultKp = 10.0;
  static constexpr double kDefaultKv = 3.0;
  static constexpr double kDefaultUpdateRateHz = 100.0;

  // Non-real-time. Throws servoloop::ConfigError for a malformed parameter, an
  // update_rate <= 0 or a joint the hardware lacks.
  bool init(hardware_interface::EffortJointInterface* hw,
            const controller_manager::ControllerContext& context) override;
  // Real-time.
  void starting(const Time& time) override;
  // Real-time.
  ReturnType update(const Time& time, const Duration& period) override;

  // After init.
  double kp() const noexcept { return kp_; }
  double kv() const noexcept { return kv_; }
  double updateRate() const noexcept { return gate_.rate(); }

  // Controller thread, or once it stopped (diagnostics and tests).
  double positionCommand() const noexcept { return position_command_; }
  double effortCommand() const noexcept { return effort_; }
  std::uint64_t controlUpdates() const noexcept { return control_updates_; }
  std::uint64_t rejectedNonFiniteCommands() const noexcept { return command_input_.rejectedNonFinite(); }

 private:
  using Float64 = servoloop::std_msgs::Float64;

  hardware_interface::JointHandle joint_;
  double kp_ = kDefaultKp;
  double kv_ = kDefaultKv;
  PeriodicGate gate_;
  ScalarCommandInput command_input_;
  servoloop::realtime::RealtimePublisher<Float64> position_publisher_;
  servoloop::realtime::RealtimePublisher<Float64> velocity_publisher_;
  servoloop::realtime::RealtimePublisher<Float64> effort_publisher_;
  servoloop::realtime::RealtimePublisher<servoloop::sensor_msgs::JointState> joint_state_publisher_;

  double position_command_ = 0.0;  // rad
  double effort_ = 0.0;            // held between control updates
  std::uint64_t control_updates_ = 0;
};

}  // namespace servoloop::controllers
