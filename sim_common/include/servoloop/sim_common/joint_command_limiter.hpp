#pragma once
// The joint limits of one simulated joint, enforced on whichever command
// interface is active, as gazebo_ros_control does: for each command interface
// the joint offers, a soft-limits handle when the URDF <safety_controller> or
// the YAML gives soft limits (and the limits it needs exist), else a
// saturation handle when the joint has the limits saturation needs, else none.
#include <optional>
#include <string>

#include "servoloop/hardware_interface/joint_limits_loader.hpp"
#include "servoloop/hardware_interface/joint_limits_interface.hpp"
#include "servoloop/core/time.hpp"
#include "servoloop/sim_common/physics_engine.hpp"
#include "servoloop/transmissions/robot_transmissions.hpp"

namespace servoloop::sim_common {

// Which handle limits a command interface.
enum class LimitEnforcement { none, saturation, soft_limits };

class JointCommandLimiter {
 public:
  JointCommandLimiter() = default;

  // Non-real-time. `values`: the joint's storage (must outlive this object;
  // the handles point into it). `offered`: the joint's command interfaces.
  // `config`: its limits, or nullptr for none. Throws servoloop::ConfigError
  // when a limit value is unusable.
  JointCommandLimiter(const std::string& joint_name, transmissions::JointValues& values,
                      const transmissions::JointCommandInterfaces& offered,
                      const hardware_interface::JointLimitsConfig* config);

  // Real-time: no allocation, no throw. Limits the command of `mode` in place
  // (nothing for JointCommandMode::none or an interface without a handle).
  void enforce(JointCommandMode mode, Duration period) noexcept;

  // Real-time safe. Forgets the previous command of the position and velocity
  // handles; call when a controller starts commanding the joint.
  void reset() noexcept;

  LimitEnforcement enforcement(JointCommandMode mode) const noexcept;

 private:
  std::optional<hardware_interface::EffortJointSoftLimitsHandle> effort_soft_limits_;
  std::optional<hardware_interface::EffortJointSaturationHandle> effort_saturation_;
  std::optional<hardware_interface::VelocityJointSoftLimitsHandle> velocity_soft_limits_;
  std::optional<hardware_interface::VelocityJointSaturationHandle> velocity_saturation_;
  std::optional<hardware_interface::PositionJointSoftLimitsHandle> position_soft_limits_;
  std::optional<hardware_interface::PositionJointSaturationHandle> position_saturation_;
};

}  // namespace servoloop::sim_common
