// Registration of the effort forward-command controllers (the classes are
// templates in controllers/common).
#include "servoloop/controllers/effort_controllers/forward_controllers.hpp"

#include "servoloop/plugin/plugin_register.hpp"

SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::effort_controllers::JointEffortController,
                          servoloop::controller_manager::ControllerBase,
                          "effort_controllers/JointEffortController")
SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::effort_controllers::JointGroupEffortController,
                          servoloop::controller_manager::ControllerBase,
                          "effort_controllers/JointGroupEffortController")
