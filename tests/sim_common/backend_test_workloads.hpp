#pragma once
// The allocation tests' workload, the same for every backend (bullet,
// mujoco, mock).
#include <string>
#include <vector>

#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/hardware_interface/simulated_robot_hw.hpp"
#include "sim_test_support.hpp"

namespace servoloop::sim_testing {

// Position limits with soft limits for the arm's joint: the allocation
// workload then goes through saturation and soft-limit handles.
inline constexpr const char* kArmLimitsWithSoftLimits =
    R"(<limit lower="-1" upper="1" effort="10" velocity="1"/>
       <safety_controller soft_lower_limit="-0.5" soft_upper_limit="0.5" k_position="10" k_velocity="2"/>)";

// The allocation tests' workload on armUrdf(…, kAllJointInterfaces, …):
// read, commands on all three joint interfaces, write, step; a controller
// switch effort → velocity → position every 10,000 cycles and the emergency
// stop engaged or released every 5,000. The handles are taken when it is
// built, so run() does nothing but cycles.
class AllModesArmWorkload {
 public:
  // velocity_scale, position_scale: the commands are scale · (k mod 11) rad/s
  // and scale · (k mod 13) rad.
  AllModesArmWorkload(hardware_interface::SimulatedRobotHW& hw, double velocity_scale, double position_scale)
      : hw_(hw),
        velocity_scale_(velocity_scale),
        position_scale_(position_scale),
        effort_({controllerClaiming("e", "EffortJointInterface", {"arm_joint"})}),
        velocity_({controllerClaiming("v", "VelocityJointInterface", {"arm_joint"})}),
        position_({controllerClaiming("p", "PositionJointInterface", {"arm_joint"})}),
        effort_handle_(hw.get<hardware_interface::EffortJointInterface>()->getHandle("arm_joint")),
        velocity_handle_(hw.get<hardware_interface::VelocityJointInterface>()->getHandle("arm_joint")),
        position_handle_(hw.get<hardware_interface::PositionJointInterface>()->getHandle("arm_joint")) {}

  // Returns the sum of the positions read (finite unless the backend blew up).
  double run(int cycles) {
    const Duration period(0.001);
    double checksum = 0.0;
    for (int k = 0; k < cycles; ++k) {
      if (k % 30000 == 0) hw_.doSwitch(effort_, position_);
      if (k % 30000 == 10000) hw_.doSwitch(velocity_, effort_);
      if (k % 30000 == 20000) hw_.doSwitch(position_, velocity_);
      if (k % 5000 == 0) hw_.setEmergencyStop((k / 5000) % 2 == 1);
      hw_.read(Time(), period);
      effort_handle_.setCommand(k % 7 - 3.0);
      velocity_handle_.setCommand(velocity_scale_ * (k % 11));
      position_handle_.setCommand(position_scale_ * (k % 13));
      hw_.write(Time(), period);
      hw_.step();
      checksum += effort_handle_.getPosition();
    }
    return checksum;
  }

 private:
  hardware_interface::SimulatedRobotHW& hw_;
  double velocity_scale_;
  double position_scale_;
  std::vector<hardware_interface::ControllerInfo> effort_, velocity_, position_;
  hardware_interface::JointHandle effort_handle_, velocity_handle_, position_handle_;
};

}  // namespace servoloop::sim_testing
