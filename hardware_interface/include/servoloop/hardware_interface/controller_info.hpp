#pragma once
#include <set>
#include <string>
#include <vector>

namespace servoloop::hardware_interface {

// Resources (joint names) a controller claims through one interface.
struct InterfaceResources {
  std::string hardware_interface;  // e.g. "EffortJointInterface"
  std::set<std::string> resources;
};

// What the manager tells the hardware about a controller when switching.
struct ControllerInfo {
  std::string name;
  std::string type;
  std::vector<InterfaceResources> claimed_resources;
};

}  // namespace servoloop::hardware_interface
