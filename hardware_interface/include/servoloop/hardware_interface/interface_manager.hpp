#pragma once
#include <map>
#include <string>
#include <typeindex>
#include <vector>

#include "servoloop/hardware_interface/hardware_interface.hpp"

namespace servoloop::hardware_interface {

// The set of interfaces a RobotHW offers, looked up by C++ type (as controllers
// do in init) or by name (as the command line and claim checks do). Not for the
// real-time path. Interfaces are owned by the registering object.
class InterfaceManager {
 public:
  template <class T>
  void registerInterface(T* iface) {
    by_type_[std::type_index(typeid(T))] = iface;
    by_name_[iface->name()] = iface;
  }

  // nullptr when the hardware does not offer T.
  template <class T>
  T* get() const {
    auto it = by_type_.find(std::type_index(typeid(T)));
    return it == by_type_.end() ? nullptr : static_cast<T*>(it->second);
  }

  HardwareInterface* getByName(const std::string& name) const {
    auto it = by_name_.find(name);
    return it == by_name_.end() ? nullptr : it->second;
  }

  std::vector<std::string> getNames() const {
    std::vector<std::string> names;
    for (const auto& [n, i] : by_name_) names.push_back(n);
    return names;
  }

 private:
  std::map<std::type_index, HardwareInterface*> by_type_;
  std::map<std::string, HardwareInterface*> by_name_;
};

}  // namespace servoloop::hardware_interface
