#pragma once
#include <map>
#include <string>
#include <vector>

#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/hardware_interface.hpp"

namespace servoloop::hardware_interface {

// Holds the handles of one interface by name. Handles are looked up at
// configure time (never on the real-time path); an unknown name throws an
// UnknownHandleError naming the handle, the interface and what it has.
// ClaimResources: whether getHandle() records a claim (command interfaces do,
// the state interface does not).
template <class HandleT, bool ClaimResources>
class ResourceManager : public HardwareInterface {
 public:
  using Handle = HandleT;

  // Registering a name twice replaces the earlier handle.
  void registerHandle(const HandleT& handle) { handles_[handle.getName()] = handle; }

  HandleT getHandle(const std::string& name) {
    auto it = handles_.find(name);
    if (it == handles_.end()) {
      std::string known;
      for (const auto& [n, h] : handles_) known += (known.empty() ? "" : ", ") + n;
      throw UnknownHandleError(std::string(this->name()) + " has no handle '" + name +
                               "' (it has: " + (known.empty() ? "none" : known) +
                               "); check the joint/actuator name and the <transmission> "
                               "hardwareInterface in the URDF");
    }
    if constexpr (ClaimResources) this->claim(name);
    return it->second;
  }

  bool hasHandle(const std::string& name) const { return handles_.count(name) != 0; }

  std::vector<std::string> getNames() const override {
    std::vector<std::string> names;
    names.reserve(handles_.size());
    for (const auto& [n, h] : handles_) names.push_back(n);
    return names;
  }

 private:
  std::map<std::string, HandleT> handles_;
};

}  // namespace servoloop::hardware_interface
