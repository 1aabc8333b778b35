#pragma once
// What a URDF <transmission> element says, after parsing and validation.
#include <string>
#include <vector>

namespace servoloop::transmissions {

// Type names as ros_control spells them in <type>.
inline constexpr const char* kSimpleTransmissionType = "transmission_interface/SimpleTransmission";
inline constexpr const char* kDifferentialTransmissionType =
    "transmission_interface/DifferentialTransmission";
inline constexpr const char* kFourBarLinkageTransmissionType =
    "transmission_interface/FourBarLinkageTransmission";

// One <joint> of a transmission.
struct TransmissionJointInfo {
  std::string name;
  // Without the "hardware_interface/" prefix, e.g. "EffortJointInterface".
  std::vector<std::string> hardware_interfaces;
  std::string role;                   // "joint1"/"joint2" for two-joint types, else usually ""
  double mechanical_reduction = 1.0;  // used by Differential and FourBarLinkage
  double offset = 0.0;                // rad or m, added to the joint position
};

// One <actuator> of a transmission.
struct TransmissionActuatorInfo {
  std::string name;
  // Without the "hardware_interface/" prefix; optional in the URDF.
  std::vector<std::string> hardware_interfaces;
  std::string role;  // "actuator1"/"actuator2" for two-actuator types
  double mechanical_reduction = 1.0;
};

struct TransmissionInfo {
  std::string name;
  std::string type;  // one of the k...TransmissionType names above
  // For Differential and FourBarLinkage the parser orders these by role
  // (joint1 then joint2, actuator1 then actuator2).
  std::vector<TransmissionJointInfo> joints;
  std::vector<TransmissionActuatorInfo> actuators;
};

}  // namespace servoloop::transmissions
