#pragma once
#include <string>

#include <yaml-cpp/yaml.h>

namespace servoloop::hardware_interface {

// Everything a RobotHW needs to configure itself.
struct HardwareInfo {
  std::string urdf_xml;         // the robot description, as text
  std::string urdf_path;        // where it came from, for error messages ("" if inline)
  std::string robot_namespace;  // e.g. "/one_DOF_robot"
  // Parameters under the robot namespace (joint_limits/<joint>/..., backend
  // settings such as physics/time_step); a null node when there are none.
  YAML::Node parameters;
};

}  // namespace servoloop::hardware_interface
