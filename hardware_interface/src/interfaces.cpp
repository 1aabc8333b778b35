// The joint and actuator interfaces' code, compiled once here rather than in
// every controller that uses them (their headers declare these instantiations
// extern).
#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/actuator_interfaces.hpp"
#include "servoloop/hardware_interface/hardware_interface.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"

namespace servoloop::hardware_interface {

HardwareInterface::~HardwareInterface() = default;

namespace detail {
void throwUnknownHandle(const char* interface_name, const std::string& handle,
                        const std::vector<std::string>& known) {
  std::string listed;
  for (const auto& name : known) listed += (listed.empty() ? "" : ", ") + name;
  throw UnknownHandleError(std::string(interface_name) + " has no handle '" + handle +
                           "' (it has: " + (listed.empty() ? "none" : listed) +
                           "); check the joint/actuator name and the <transmission> "
                           "hardwareInterface in the URDF");
}
}  // namespace detail

template class ResourceManager<JointStateHandle, false>;
template class ResourceManager<JointHandle, true>;
template class ResourceManager<ActuatorStateHandle, false>;
template class ResourceManager<ActuatorHandle, true>;

const char* JointStateInterface::name() const { return "JointStateInterface"; }
const char* EffortJointInterface::name() const { return "EffortJointInterface"; }
const char* VelocityJointInterface::name() const { return "VelocityJointInterface"; }
const char* PositionJointInterface::name() const { return "PositionJointInterface"; }
const char* ActuatorStateInterface::name() const { return "ActuatorStateInterface"; }
const char* EffortActuatorInterface::name() const { return "EffortActuatorInterface"; }
const char* VelocityActuatorInterface::name() const { return "VelocityActuatorInterface"; }
const char* PositionActuatorInterface::name() const { return "PositionActuatorInterface"; }

}  // namespace servoloop::hardware_interface
