#pragma once
#include <map>
#include <string>
#include <vector>

#include "servoloop/hardware_interface/hardware_interface.hpp"

namespace servoloop::hardware_interface {

namespace detail {
// Throws the UnknownHandleError of ResourceManager::getHandle (out of line, so
// that each interface's code stays small).
[[noreturn]] void throwUnknownHandle(const char* interface_name, const std::string& handle,
                                     const std::vector<std::string>& known);
}  // namespace detail

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
    if (it == handles_.end()) detail::throwUnknownHandle(this->name(), name, getNames());
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
