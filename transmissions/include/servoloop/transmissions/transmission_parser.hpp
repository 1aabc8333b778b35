#pragma once
#include <memory>
#include <string>
#include <vector>

#include "servoloop/transmissions/transmission.hpp"
#include "servoloop/transmissions/transmission_info.hpp"

namespace servoloop::transmissions {

// Non-real-time. Reads every <transmission> directly under <robot> in
// urdf_xml, in document order, and validates it against the robot's joints.
// source_name names the description in messages (usually the file name).
//
// Accepted forms follow ros_control: the type as a <type> child or as the
// legacy type="..." attribute, with or without the "transmission_interface/"
// prefix; <hardwareInterface> with or without the "hardware_interface/" prefix.
//
// Throws servoloop::ConfigError when the XML or robot cannot be read, or when
// any transmission is malformed; the message has one line per problem, each
// naming the file, the transmission and the fix, e.g.
//   one_dof.urdf: transmission 'tran1': actuator 'motor1' has no <mechanicalReduction>; add ...
std::vector<TransmissionInfo> parseTransmissions(const std::string& urdf_xml,
                                                 const std::string& source_name);

// Non-real-time. Builds the transmission an info describes (joints and
// actuators taken in the order the info lists them). Throws
// servoloop::ConfigError for an unknown type, wrong joint/actuator counts or
// zero reductions, naming the transmission.
std::unique_ptr<Transmission> makeTransmission(const TransmissionInfo& info);

}  // namespace servoloop::transmissions
