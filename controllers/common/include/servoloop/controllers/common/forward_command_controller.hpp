#pragma once
// A controller that forwards the command it receives to one joint, unchanged,
// as ros_control's forward_command_controller: the joint's effort, velocity or
// position command (by Interface) is written every cycle.
//
// Parameters: joint (required).
// Topic: <robot ns>/<controller>/command, std_msgs/Float64.
// Starting: the command is 0 for effort and velocity interfaces and the
// joint's current position for the position interface (the joint holds).
#include <cstdint>
#include <string>
#include <type_traits>

#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/controllers/common/command_input.hpp"
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
    return true;
  }

  // Real-time.
  void starting(const Time& /*time*/) override {
    command_ = kStartsAtCurrentPosition ? joint_.getPosition() : 0.0;
    command_input_.clear();
  }

  // Real-time.
  ReturnType update(const Time& /*time*/, const Duration& /*period*/) override {
    command_input_.takeNew(command_);
    joint_.setCommand(command_);
    return ReturnType::ok;
  }

  // Controller thread, or once it stopped (diagnostics and tests).
  double command() const noexcept { return command_; }
  const std::string& jointName() const { return joint_.getName(); }
  std::uint64_t rejectedNonFiniteCommands() const noexcept { return command_input_.rejectedNonFinite(); }

 private:
  hardware_interface::JointHandle joint_;
  ScalarCommandInput command_input_;
  double command_ = 0.0;  // the last accepted command, written every cycle
};

}  // namespace servoloop::controllers
