#pragma once
// Getting (and so claiming) the joint handles a controller's parameters name.
// Non-real-time.
#include <string>
#include <vector>

#include "servoloop/controller_manager/controller_context.hpp"
#include "servoloop/controllers/common/controller_params.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::controllers {

// The handle of joint_name from iface (claiming it on a command interface).
// Throws servoloop::ConfigError naming the controller, the parameter
// (parameter_key) and the joints the interface has.
template <class Interface>
typename Interface::Handle getJointHandle(Interface& iface, const std::string& joint_name,
                                          const ControllerContext& context,
                                          const std::string& parameter_key) {
  try {
    return iface.getHandle(joint_name);
  } catch (const UnknownHandleError& e) {
    throw ConfigError("controller '" + context.name + "': parameter '" +
                      parameterPath(context, parameter_key) + "' names joint '" + joint_name +
                      "', which the hardware does not offer: " + e.what());
  }
}

template <class Interface>
std::vector<typename Interface::Handle> getJointHandles(Interface& iface,
                                                        const std::vector<std::string>& joint_names,
                                                        const ControllerContext& context,
                                                        const std::string& parameter_key) {
  std::vector<typename Interface::Handle> handles;
  handles.reserve(joint_names.size());
  for (const auto& name : joint_names) {
    handles.push_back(getJointHandle(iface, name, context, parameter_key));
  }
  return handles;
}

}  // namespace servoloop::controllers
