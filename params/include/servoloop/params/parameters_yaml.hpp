#pragma once
// Between parameter views and yaml-cpp, for the code that holds parameters as
// YAML (the parameter store, the controller manager, tests). Controllers and
// backends read parameters through Parameters alone (parameters.hpp).
#include <string>

#include <yaml-cpp/yaml.h>

#include "servoloop/params/parameters.hpp"

namespace servoloop::params {

// A view of a copy of node (later changes to node do not show), named path,
// e.g. "/one_DOF_robot/joint1_position_controller".
Parameters parametersFromYaml(const YAML::Node& node, std::string path);

// The YAML under a view (a copy), for code that needs the raw tree.
YAML::Node toYaml(const Parameters& parameters);

}  // namespace servoloop::params
