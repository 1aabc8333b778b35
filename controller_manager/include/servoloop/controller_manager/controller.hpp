#pragma once
// A controller that works through one hardware interface, as ros_control's
// controller_interface::Controller<T>:
//
//   class MyController : public Controller<hardware_interface::EffortJointInterface> {
//     bool init(hardware_interface::EffortJointInterface* hw, const ControllerContext& ctx) override {
//       joint_ = hw->getHandle(ctx.params["joint"].as<std::string>());  // claims the joint
//       return true;
//     }
//     ReturnType update(const Time&, const Duration& period) override { ... }
//   };
#include <string>
#include <vector>

#include "servoloop/controller_manager/controller_base.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/actuator_interfaces.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"

namespace servoloop::controller_manager {

namespace detail {
// "JointStateInterface, EffortJointInterface" or "none".
std::string joinInterfaceNames(const std::vector<std::string>& names);

// The message for a controller whose hardware lacks the interfaces it needs.
std::string missingInterfaceMessage(const std::string& controller_name,
                                    const std::vector<std::string>& missing,
                                    const std::vector<std::string>& offered);

template <class Interface>
std::string interfaceName() {
  Interface probe;  // interfaces are cheap to build; name() is virtual
  return probe.name();
}
}  // namespace detail

template <class Interface>
class Controller : public ControllerBase {
 public:
  using InterfaceType = Interface;

  // Non-real-time. The controller's own set-up: read parameters from
  // context.params, get handles from hw (getHandle on a command interface
  // claims the resource). Return false, or throw servoloop::ConfigError naming
  // the parameter and the fix, when it cannot run.
  virtual bool init(Interface* /*hw*/, const ControllerContext& /*context*/) { return true; }

  // Non-real-time. Implements the ControllerBase contract for one interface.
  bool initRequest(hardware_interface::RobotHW* robot_hw, const ControllerContext& context,
                   std::vector<hardware_interface::InterfaceResources>& claimed_resources) final {
    if (isInitialized()) {
      throw Error("controller '" + context.name + "': initRequest called twice");
    }
    Interface* iface = robot_hw == nullptr ? nullptr : robot_hw->template get<Interface>();
    if (iface == nullptr) {
      throw ConfigError(detail::missingInterfaceMessage(
          context.name, {detail::interfaceName<Interface>()},
          robot_hw == nullptr ? std::vector<std::string>{} : robot_hw->getNames()));
    }
    // Claims left over from an earlier controller's init must not count as ours.
    iface->clearClaims();
    claimed_resources.clear();
    clearClaimedCommands();
    bool ok = false;
    try {
      ok = init(iface, context);
    } catch (...) {
      iface->clearClaims();
      throw;
    }
    if (!ok) {
      iface->clearClaims();
      return false;
    }
    recordClaimedCommands(iface, claimed_resources);
    iface->clearClaims();
    markInitialized();
    return true;
  }
};

// Controllers of ros_control's joint and actuator interfaces share one
// instantiation each, in the controller_manager library (controller.cpp):
// a controller's own source then compiles only its own code.
extern template class Controller<hardware_interface::JointStateInterface>;
extern template class Controller<hardware_interface::EffortJointInterface>;
extern template class Controller<hardware_interface::VelocityJointInterface>;
extern template class Controller<hardware_interface::PositionJointInterface>;
extern template class Controller<hardware_interface::EffortActuatorInterface>;
extern template class Controller<hardware_interface::VelocityActuatorInterface>;
extern template class Controller<hardware_interface::PositionActuatorInterface>;

}  // namespace servoloop::controller_manager
