#pragma once
// The group form of ForwardCommandController, as ros_control's
// forward_command_controller::ForwardJointGroupCommandController: one command
// per joint, forwarded unchanged every cycle.
//
// Parameters: joints (required list).
// Topic: <robot ns>/<controller>/command, std_msgs/Float64MultiArray with one
// value per joint in the order of `joints`; a command of another length, or
// with a non-finite value, is ignored (counted, and the first one logged).
// Starting: commands are 0 for effort and velocity interfaces and the joints'
// current positions for the position interface.
// command_timeout (s, default 0 = off): with no command for that long, the
// commands go back to those starting values, measured then (see
// command_timeout.hpp).
#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/controllers/common/command_input.hpp"
#include "servoloop/controllers/common/command_timeout.hpp"
#include "servoloop/controllers/common/controller_params.hpp"
#include "servoloop/controllers/common/joint_handles.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"

namespace servoloop::controllers {

template <class Interface>
class ForwardJointGroupCommandController : public controller_manager::Controller<Interface> {
 public:
  static constexpr bool kStartsAtCurrentPosition =
      std::is_base_of_v<hardware_interface::PositionJointInterface, Interface>;

  // Non-real-time.
  bool init(Interface* hw, const ControllerContext& context) override {
    const std::vector<std::string> joint_names =
        requireStringList(context, "joints", "joints: [joint1, joint2]");
    joints_ = getJointHandles(*hw, joint_names, context, "joints");
    commands_.assign(joints_.size(), 0.0);
    command_input_.connect(context.topics, controllerTopic(context, "command"), joints_.size(),
                           context.name);
    timeout_.init(context, kStartsAtCurrentPosition ? "the joints hold the positions they have then"
                                                    : "the commands go to 0");
    return true;
  }

  // Real-time.
  void starting(const Time& time) override {
    setSafeCommands();
    command_input_.clear();
    timeout_.restart(time);
  }

  // Real-time.
  ReturnType update(const Time& time, const Duration& /*period*/) override {
    if (command_input_.takeNew(commands_)) {
      timeout_.restart(time);
    } else if (timeout_.expired(time)) {
      setSafeCommands();
    }
    for (std::size_t i = 0; i < joints_.size(); ++i) joints_[i].setCommand(commands_[i]);
    return ReturnType::ok;
  }

  // Controller thread, or once it stopped (diagnostics and tests).
  const std::vector<double>& commands() const noexcept { return commands_; }
  std::uint64_t rejectedNonFiniteCommands() const noexcept { return command_input_.rejectedNonFinite(); }
  std::uint64_t rejectedWrongSizeCommands() const noexcept { return command_input_.rejectedWrongSize(); }
  std::uint64_t commandTimeouts() const noexcept { return timeout_.count(); }

 private:
  // Zero efforts or velocities; for positions, where the joints are.
  void setSafeCommands() noexcept {
    for (std::size_t i = 0; i < joints_.size(); ++i) {
      commands_[i] = kStartsAtCurrentPosition ? joints_[i].getPosition() : 0.0;
    }
  }

  std::vector<hardware_interface::JointHandle> joints_;
  ArrayCommandInput command_input_;
  CommandTimeout timeout_;
  std::vector<double> commands_;  // the last accepted commands, in `joints` order
};

}  // namespace servoloop::controllers
