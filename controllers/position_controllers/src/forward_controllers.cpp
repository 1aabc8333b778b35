// Registration of the position_controllers package (the classes are templates in
// controllers/common).
#include "servoloop/controllers/position_controllers/forward_controllers.hpp"

#include "servoloop/plugin/plugin_register.hpp"

SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::position_controllers::JointPositionController,
                          servoloop::controller_manager::ControllerBase,
                          "position_controllers/JointPositionController")
SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::position_controllers::JointGroupPositionController,
                          servoloop::controller_manager::ControllerBase,
                          "position_controllers/JointGroupPositionController")
