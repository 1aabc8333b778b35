#include "joint_limits_handle_support.hpp"

#include <string>

#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/joint_limits_validation.hpp"

namespace servoloop::hardware_interface::detail {
namespace {

[[noreturn]] void throwMissing(const JointHandle& joint_handle, const char* handle_kind,
                               const char* what, const char* urdf_attributes,
                               const char* yaml_keys) {
  const std::string& joint = joint_handle.getName();
  throw Error("joint '" + joint + "': " + handle_kind + " needs " + what + "; add " +
              urdf_attributes + " to the joint's URDF <limit> or " + yaml_keys +
              " under joint_limits/" + joint);
}

}  // namespace

void requireValidHandle(const JointHandle& joint_handle, const JointLimits& limits,
                        const char* handle_kind) {
  if (!joint_handle.valid() || joint_handle.getCommandPtr() == nullptr) {
    throw Error(std::string(handle_kind) +
                ": the joint handle is empty; get it from the joint's command interface");
  }
  validateJointLimits(joint_handle.getName(), limits);
}

void requireVelocityLimits(const JointHandle& joint_handle, const JointLimits& limits,
                           const char* handle_kind) {
  if (limits.has_velocity_limits) return;
  throwMissing(joint_handle, handle_kind, "a velocity limit", "velocity=\"…\"",
               "has_velocity_limits: true and max_velocity");
}

void requireEffortLimits(const JointHandle& joint_handle, const JointLimits& limits,
                         const char* handle_kind) {
  if (limits.has_effort_limits) return;
  throwMissing(joint_handle, handle_kind, "an effort limit", "effort=\"…\"",
               "has_effort_limits: true and max_effort");
}

}  // namespace servoloop::hardware_interface::detail
