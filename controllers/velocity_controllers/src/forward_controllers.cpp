// Registration of the velocity_controllers package (the classes are templates in
// controllers/common).
#include "servoloop/controllers/velocity_controllers/forward_controllers.hpp"

#include "servoloop/plugin/plugin_register.hpp"

SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::velocity_controllers::JointVelocityController,
                          servoloop::controller_manager::ControllerBase,
                          "velocity_controllers/JointVelocityController")
SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::velocity_controllers::JointGroupVelocityController,
                          servoloop::controller_manager::ControllerBase,
                          "velocity_controllers/JointGroupVelocityController")
