#include "servoloop/hardware_interface/robot_hw.hpp"

#include <map>
#include <string>

namespace servoloop::hardware_interface {

bool RobotHW::checkForConflict(const std::vector<ControllerInfo>& running) const {
  // resource -> the controller that first claimed it
  std::map<std::string, const std::string*> owner;
  for (const auto& controller : running) {
    for (const auto& claimed : controller.claimed_resources) {
      for (const auto& resource : claimed.resources) {
        auto [it, inserted] = owner.emplace(resource, &controller.name);
        if (!inserted && *it->second != controller.name) return true;
      }
    }
  }
  return false;
}

bool RobotHW::prepareSwitch(const std::vector<ControllerInfo>&,
                            const std::vector<ControllerInfo>&) {
  return true;
}

ReturnType RobotHW::doSwitch(const std::vector<ControllerInfo>&, const std::vector<ControllerInfo>&) {
  return ReturnType::ok;
}

}  // namespace servoloop::hardware_interface
