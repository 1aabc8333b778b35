#pragma once
// The joint limits of a robot, enforced in one call per cycle. A RobotHW (or
// the control loop) builds one handle per limited joint at configure time,
// registers it here, and calls enforceLimits(period) after the controllers'
// update and before the joint→actuator transmissions and write().
#include <string>
#include <vector>

#include "servoloop/hardware_interface/effort_joint_saturation_handle.hpp"
#include "servoloop/hardware_interface/effort_joint_soft_limits_handle.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/hardware_interface.hpp"
#include "servoloop/hardware_interface/position_joint_saturation_handle.hpp"
#include "servoloop/hardware_interface/position_joint_soft_limits_handle.hpp"
#include "servoloop/core/time.hpp"
#include "servoloop/hardware_interface/velocity_joint_saturation_handle.hpp"
#include "servoloop/hardware_interface/velocity_joint_soft_limits_handle.hpp"

namespace servoloop::hardware_interface {

// HandleT: one of the *JointSaturationHandle / *JointSoftLimitsHandle classes
// (anything with getName(), enforceLimits(Duration) noexcept and a static
// kInterfaceName; reset() noexcept is used when it has one).
// Handles sit in one contiguous array in registration order; claims nothing.
template <class HandleT>
class JointLimitsInterface : public HardwareInterface {
 public:
  using Handle = HandleT;

  const char* name() const override { return HandleT::kInterfaceName; }

  // Non-real-time. Registering a joint twice replaces its earlier handle.
  void registerHandle(const HandleT& handle) {
    for (HandleT& registered : handles_) {
      if (registered.getName() == handle.getName()) {
        registered = handle;
        return;
      }
    }
    handles_.push_back(handle);
  }

  bool hasHandle(const std::string& joint_name) const {
    for (const HandleT& handle : handles_) {
      if (handle.getName() == joint_name) return true;
    }
    return false;
  }

  // Non-real-time. Throws servoloop::UnknownHandleError naming the joint and
  // the joints this interface limits.
  HandleT& getHandle(const std::string& joint_name) {
    for (HandleT& handle : handles_) {
      if (handle.getName() == joint_name) return handle;
    }
    std::string known;
    for (const HandleT& handle : handles_) known += (known.empty() ? "" : ", ") + handle.getName();
    throw UnknownHandleError(std::string(name()) + " has no handle for joint '" + joint_name +
                             "' (it has: " + (known.empty() ? "none" : known) + ")");
  }

  std::vector<std::string> getNames() const override {
    std::vector<std::string> names;
    names.reserve(handles_.size());
    for (const HandleT& handle : handles_) names.push_back(handle.getName());
    return names;
  }

  std::size_t size() const { return handles_.size(); }

  // Real-time: no allocation, no throw. Limits every registered joint's command.
  void enforceLimits(Duration period) noexcept {
    for (HandleT& handle : handles_) handle.enforceLimits(period);
  }

  // Real-time safe. Forgets every handle's previous command (a no-op for the
  // stateless handles). Call when the controllers writing these joints restart.
  void reset() noexcept {
    if constexpr (requires(HandleT& handle) { handle.reset(); }) {
      for (HandleT& handle : handles_) handle.reset();
    }
  }

 private:
  std::vector<HandleT> handles_;
};

using EffortJointSaturationInterface = JointLimitsInterface<EffortJointSaturationHandle>;
using EffortJointSoftLimitsInterface = JointLimitsInterface<EffortJointSoftLimitsHandle>;
using PositionJointSaturationInterface = JointLimitsInterface<PositionJointSaturationHandle>;
using PositionJointSoftLimitsInterface = JointLimitsInterface<PositionJointSoftLimitsHandle>;
using VelocityJointSaturationInterface = JointLimitsInterface<VelocityJointSaturationHandle>;
using VelocityJointSoftLimitsInterface = JointLimitsInterface<VelocityJointSoftLimitsHandle>;

}  // namespace servoloop::hardware_interface
