#pragma once
// Small robots and helpers shared by the simulation backend tests
// (tests/sim_common, tests/sim_mock, tests/sim_bullet_hw, tests/sim_mujoco).
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <yaml-cpp/yaml.h>

#include "servoloop/hardware_interface/controller_info.hpp"
#include "servoloop/hardware_interface/hardware_info.hpp"
#include "servoloop/hardware_interface/joint_handle.hpp"
#include "servoloop/hardware_interface/simulated_robot_hw.hpp"

namespace servoloop::sim_testing {

inline std::string readFile(const std::string& path) {
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

// The seed's one-DOF robot: without transmissions (joint1 continuous), or with
// tran1/motor1 (joint1 revolute, limits effort 10, [0, 2] rad, 0.5 rad/s, damping 1).
inline std::string seedUrdfPath(bool with_joint_control) {
  return std::string(SERVOLOOP_SOURCE_DIR) + "/robots/one_dof/" +
         (with_joint_control ? "minimal_robot_description_w_jnt_ctl.urdf"
                             : "minimal_robot_description.urdf");
}

// Inertia of the seed's link2 about joint1's axis (y): iyy at the centre of
// mass plus m·d² with d = 0.5 m: 0.1 + 1·0.25.
inline constexpr double kSeedLink2AxisInertia = 0.35;

// A one-joint arm: `joint_type` joint "arm_joint" about y at the world origin,
// link "arm" of 1 kg whose centre of mass lies `com_x` m along x, iyy 0.01
// kg·m² there (so 0.01 + com_x² about the joint axis). One SimpleTransmission
// "arm_transmission" with `reduction` to actuator "arm_motor", offering
// `interfaces` (e.g. "<hardwareInterface>EffortJointInterface</hardwareInterface>").
// `joint_extra`: more XML inside <joint> (e.g. <limit>, <safety_controller>).
inline std::string armUrdf(double reduction, const std::string& interfaces,
                           const std::string& joint_type = "continuous",
                           const std::string& joint_extra = "", double com_x = 1.0,
                           double joint_offset = 0.0) {
  std::ostringstream xml;
  xml << R"(<?xml version="1.0"?>
<robot name="arm_robot">
  <link name="world"/>
  <joint name="arm_joint" type=")"
      << joint_type << R"(">
    <parent link="world"/>
    <child link="arm"/>
    <axis xyz="0 1 0"/>
    )" << joint_extra
      << R"(
  </joint>
  <link name="arm">
    <inertial>
      <origin xyz=")"
      << com_x << R"( 0 0"/>
      <mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
    </inertial>
  </link>
  <transmission name="arm_transmission">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="arm_joint">
      )" << interfaces
      << R"(
      <offset>)"
      << joint_offset << R"(</offset>
    </joint>
    <actuator name="arm_motor">
      <mechanicalReduction>)"
      << reduction << R"(</mechanicalReduction>
    </actuator>
  </transmission>
</robot>
)";
  return xml.str();
}

inline constexpr const char* kEffortInterface =
    "<hardwareInterface>EffortJointInterface</hardwareInterface>";
inline constexpr const char* kAllJointInterfaces =
    "<hardwareInterface>EffortJointInterface</hardwareInterface>"
    "<hardwareInterface>VelocityJointInterface</hardwareInterface>"
    "<hardwareInterface>PositionJointInterface</hardwareInterface>";

// `yaml`: the map of the robot namespace (what sits under `one_DOF_robot:`).
inline hardware_interface::HardwareInfo makeInfo(const std::string& urdf_xml,
                                                 const std::string& yaml = "",
                                                 const std::string& urdf_path = "") {
  hardware_interface::HardwareInfo info;
  info.urdf_xml = urdf_xml;
  info.urdf_path = urdf_path;
  info.robot_namespace = "/robot";
  info.parameters = yaml.empty() ? YAML::Node() : YAML::Load(yaml);
  return info;
}

inline hardware_interface::ControllerInfo controllerClaiming(const std::string& name,
                                                             const std::string& interface_name,
                                                             const std::set<std::string>& joints) {
  hardware_interface::ControllerInfo info;
  info.name = name;
  info.type = "test/Controller";
  info.claimed_resources.push_back({interface_name, joints});
  return info;
}

// The control period of cycle() (s): the backends' default time step.
inline constexpr double kCycleDt = 0.001;

// One control cycle as a controller sees it: read, `command` through
// `handle`, write, one physics step, and read again so that the handle shows
// the step's result.
inline void cycle(hardware_interface::SimulatedRobotHW& hw, hardware_interface::JointHandle& handle,
                  double command) {
  const Duration period(kCycleDt);
  hw.read(Time(), period);
  handle.setCommand(command);
  hw.write(Time(), period);
  hw.step();
  hw.read(Time(), period);
}

}  // namespace servoloop::sim_testing
