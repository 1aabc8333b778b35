#pragma once
// A controller that works through several hardware interfaces at once, as
// ros_control's MultiInterfaceController<T1, T2, ...>:
//
//   class Arm : public MultiInterfaceController<hardware_interface::EffortJointInterface,
//                                               hardware_interface::JointStateInterface> {
//     bool init(hardware_interface::RobotHW* hw, const ControllerContext& ctx) override {
//       auto* effort = hw->get<hardware_interface::EffortJointInterface>();
//       ...
//     }
//   };
//
// init sees only the listed interfaces (hw->get<Other>() is null), so every
// claim it makes is recorded, per interface.
#include <string>
#include <vector>

#include "servoloop/controller_manager/controller.hpp"

namespace servoloop::controller_manager {

namespace detail {
// The requested subset of a RobotHW's interfaces, handed to a
// MultiInterfaceController's init. It is never read or written.
class InterfaceSubset final : public hardware_interface::RobotHW {
 public:
  void init(const hardware_interface::HardwareInfo&) override {}
  ReturnType read(Time, Duration) override { return ReturnType::ok; }
  ReturnType write(Time, Duration) override { return ReturnType::ok; }
};
}  // namespace detail

template <class... Interfaces>
class MultiInterfaceController : public ControllerBase {
  static_assert(sizeof...(Interfaces) > 0, "MultiInterfaceController needs at least one interface");

 public:
  // allow_optional_interfaces: when true, interfaces the hardware lacks are
  // left out of init's RobotHW instead of failing the load.
  explicit MultiInterfaceController(bool allow_optional_interfaces = false)
      : allow_optional_interfaces_(allow_optional_interfaces) {}

  // Non-real-time. robot_hw holds only the interfaces listed in the template
  // arguments that the hardware offers. Return false, or throw
  // servoloop::ConfigError naming the parameter and the fix, when the
  // controller cannot run.
  virtual bool init(hardware_interface::RobotHW* /*robot_hw*/, const ControllerContext& /*context*/) {
    return true;
  }

  bool initRequest(hardware_interface::RobotHW* robot_hw, const ControllerContext& context,
                   std::vector<hardware_interface::InterfaceResources>& claimed_resources) final {
    if (isInitialized()) {
      throw Error("controller '" + context.name + "': initRequest called twice");
    }
    std::vector<std::string> missing;
    ((robot_hw == nullptr || robot_hw->template get<Interfaces>() == nullptr
          ? missing.push_back(detail::interfaceName<Interfaces>())
          : void()),
     ...);
    const bool all_missing = missing.size() == sizeof...(Interfaces);
    if (!missing.empty() && (!allow_optional_interfaces_ || all_missing)) {
      throw ConfigError(detail::missingInterfaceMessage(
          context.name, missing,
          robot_hw == nullptr ? std::vector<std::string>{} : robot_hw->getNames()));
    }

    detail::InterfaceSubset subset;
    (addToSubset<Interfaces>(robot_hw, subset), ...);
    clearAllClaims(robot_hw);
    claimed_resources.clear();
    clearClaimedCommands();
    bool ok = false;
    try {
      ok = init(&subset, context);
    } catch (...) {
      clearAllClaims(robot_hw);
      throw;
    }
    if (!ok) {
      clearAllClaims(robot_hw);
      return false;
    }
    (recordIfPresent<Interfaces>(robot_hw, claimed_resources), ...);
    clearAllClaims(robot_hw);
    markInitialized();
    return true;
  }

 private:
  template <class Interface>
  static void addToSubset(hardware_interface::RobotHW* robot_hw, detail::InterfaceSubset& subset) {
    if (Interface* iface = robot_hw->template get<Interface>()) subset.registerInterface(iface);
  }

  static void clearAllClaims(hardware_interface::RobotHW* robot_hw) {
    ((robot_hw->template get<Interfaces>() != nullptr
          ? robot_hw->template get<Interfaces>()->clearClaims()
          : void()),
     ...);
  }

  template <class Interface>
  void recordIfPresent(hardware_interface::RobotHW* robot_hw,
                       std::vector<hardware_interface::InterfaceResources>& claimed_resources) {
    if (Interface* iface = robot_hw->template get<Interface>()) {
      recordClaimedCommands(iface, claimed_resources);
    }
  }

  bool allow_optional_interfaces_;
};

}  // namespace servoloop::controller_manager
