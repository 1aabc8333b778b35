#pragma once
// A controller that forwards the command it receives to one joint, unchanged,
// as ros_control's forward_command_controller: the joint's effort, velocity or
// position command (by Interface) is written every cycle.
//
// Parameters: joint (required); command_timeout (s, default 0 = off): with no
// command for that long the command goes to 0 for effort and velocity
// interfaces and to the joint's measured position for the position interface
// (it holds), until the next command (see command_timeout.hpp).
// Topic: <robot ns>/<controller>/command, std_msgs/Float64.
// Starting: the command is 0 for effort and velocity interfaces and the
// joint's current position for the position interface (the joint holds).
#include <cstdint>
#include <string>
#include <type_traits>

#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/controllers/common/command_input.hpp"
#include "servoloop/controllers/common/command_timeout.hpp"
#include "servoloop/controllers/common/controller_params.hpp"
#include "servoloop/controllers/common/joint_handles.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"

namespace servoloop::controllers {

template <class Interface>
class ForwardCommandController : public controller_manager::Controller<Interface> {
 public:
  static constexpr bool kStartsAtCurrentPosition =
      std::is_base_of_v<hardware_interface::PositionJointInterface, Interface>;

  // Non-real-time.
  bool init(Interface* hw, const ControllerContext& context) override {
    const std::string joint_name = requireString(context, "joint", "joint: joint1");
    joint_ = getJointHandle(*hw, joint_name, context, "joint");
    command_input_.connect(context.topics, controllerTopic(context, "command"), context.name);
    timeout_.init(context, kStartsAtCurrentPosition ? "the joint holds the position it has then"
                                                    : "the command goes to 0");
    return true;
  }

  // Real-time.
  void starting(const Time& time) override {
    command_ = safeCommand();
    command_input_.clear();
    timeout_.restart(time);
  }

  // Real-time.
  ReturnType update(const Time& time, const Duration& /*period*/) override {
    if (command_input_.takeNew(command_)) {
      timeout_.restart(time);
    } else if (timeout_.expired(time)) {
      command_ = safeCommand();
    }
    joint_.setCommand(command_);
    return ReturnType::ok;
  }

  // Controller thread, or once it stopped (diagnostics and tests).
  double command() const noexcept { return command_; }
  const std::string& jointName() const { return joint_.getName(); }
  std::uint64_t rejectedNonFiniteCommands() const noexcept { return command_input_.rejectedNonFinite(); }
  std::uint64_t commandTimeouts() const noexcept { return timeout_.count(); }

 private:
  // Zero effort or velocity; for positions, where the joint is.
  double safeCommand() const noexcept { return kStartsAtCurrentPosition ? joint_.getPosition() : 0.0; }

  hardware_interface::JointHandle joint_;
  ScalarCommandInput command_input_;
  CommandTimeout timeout_;
  double command_ = 0.0;  // the last accepted command, written every cycle
};

}  // namespace servoloop::controllers
