#pragma once
// effort_controllers/JointGroupPositionController: JointPositionController for
// several joints at once, one PID per joint, one command topic for all.
//
// Parameters (under <robot ns>/<controller>):
//   joints       required list of joints (claimed on EffortJointInterface)
//   <joint>/pid  required for every joint, control_toolbox keys as for
//                JointPositionController (as ros_control reads them)
// Topic: <robot ns>/<controller>/command, std_msgs/Float64MultiArray in, one
// position setpoint per joint in `joints` order; a command of another length,
// or with a non-finite value, is ignored (counted, the first one logged).
// Each update, per joint: setpoint clamped and error computed by URDF joint
// type exactly as in JointPositionController; effort = PID(error, period).
// Starting: setpoints = current positions (clamped), PIDs reset.
#include <cstdint>
#include <memory>
#include <vector>

#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/controllers/common/command_input.hpp"
#include "servoloop/controllers/common/joint_position_error.hpp"
#include "servoloop/controllers/pid.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"

namespace servoloop::controllers::effort_controllers {

class JointGroupPositionController
    : public controller_manager::Controller<hardware_interface::EffortJointInterface> {
 public:
  // Non-real-time. Throws servoloop::ConfigError for a missing joints list or
  // <joint>/pid, a joint the hardware or the URDF lacks.
  bool init(hardware_interface::EffortJointInterface* hw,
            const controller_manager::ControllerContext& context) override;
  // Real-time.
  void starting(const Time& time) override;
  // Real-time.
  ReturnType update(const Time& time, const Duration& period) override;

  // Any thread: joint i's PID (in `joints` order).
  Pid& pid(std::size_t joint_index) noexcept { return pids_[joint_index]; }
  // Non-real-time: each joint's PID, as "<joint>/pid".
  std::vector<controller_manager::TunablePid> tunablePids() override { return tunable_pids_; }

  // Controller thread, or once it stopped (diagnostics and tests).
  const std::vector<double>& setpoints() const noexcept { return setpoints_; }
  const std::vector<double>& effortCommands() const noexcept { return efforts_; }
  std::uint64_t rejectedNonFiniteCommands() const noexcept { return command_input_.rejectedNonFinite(); }
  std::uint64_t rejectedWrongSizeCommands() const noexcept { return command_input_.rejectedWrongSize(); }

 private:
  std::vector<hardware_interface::JointHandle> joints_;
  std::vector<JointPositionError> position_errors_;
  std::unique_ptr<Pid[]> pids_;  // Pid holds a mutex: not movable, so not in a vector
  std::vector<controller_manager::TunablePid> tunable_pids_;
  ArrayCommandInput command_input_;

  std::vector<double> setpoints_;  // clamped to each joint's position limits
  std::vector<double> efforts_;
};

}  // namespace servoloop::controllers::effort_controllers
