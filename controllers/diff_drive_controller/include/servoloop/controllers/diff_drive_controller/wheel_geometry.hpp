#pragma once
// A differential drive's wheel separation and radius read from the robot's
// URDF when the parameters do not give them, as ros_controllers does: the
// radius is that of the wheel link's collision cylinder or sphere, the
// separation the distance between the left and right wheel joints' origins
// (the first wheel of each side). Non-real-time.
#include <string>

#include <urdf_model/model.h>

namespace servoloop::controllers::diff_drive_controller {

// Throws servoloop::ConfigError naming the joint or link and the parameter
// to give instead, when the model lacks the joint or a usable collision shape.
double wheelSeparationFromUrdf(const urdf::ModelInterface& model, const std::string& left_joint,
                               const std::string& right_joint, const std::string& controller_name);
double wheelRadiusFromUrdf(const urdf::ModelInterface& model, const std::string& wheel_joint,
                           const std::string& controller_name);

}  // namespace servoloop::controllers::diff_drive_controller
