#include <utility>

#include "servoloop/hardware_interface/actuator_handle.hpp"
#include "servoloop/hardware_interface/actuator_state_handle.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/joint_handle.hpp"
#include "servoloop/hardware_interface/joint_state_handle.hpp"

namespace servoloop::hardware_interface {
namespace {
void requireData(const void* p, const std::string& handle, const char* what) {
  if (p == nullptr) {
    throw Error("handle '" + handle + "': " + what + " data pointer is null");
  }
}
}  // namespace

JointStateHandle::JointStateHandle(std::string name, const double* position,
                                   const double* velocity, const double* effort)
    : name_(std::move(name)), position_(position), velocity_(velocity), effort_(effort) {
  requireData(position, name_, "position");
  requireData(velocity, name_, "velocity");
  requireData(effort, name_, "effort");
}

JointHandle::JointHandle(const JointStateHandle& state, double* command)
    : JointStateHandle(state), command_(command) {
  requireData(command, state.getName(), "command");
}

ActuatorStateHandle::ActuatorStateHandle(std::string name, const double* position,
                                         const double* velocity, const double* effort)
    : name_(std::move(name)), position_(position), velocity_(velocity), effort_(effort) {
  requireData(position, name_, "position");
  requireData(velocity, name_, "velocity");
  requireData(effort, name_, "effort");
}

ActuatorHandle::ActuatorHandle(const ActuatorStateHandle& state, double* command)
    : ActuatorStateHandle(state), command_(command) {
  requireData(command, state.getName(), "command");
}

}  // namespace servoloop::hardware_interface
