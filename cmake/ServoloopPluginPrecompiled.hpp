#pragma once
// The servoloop headers nearly every plugin includes: the controller and
// hardware bases, the interfaces, the topic bus and its messages, the
// registration macro. servoloop_add_plugin precompiles this file once per
// plugin target of an out-of-tree project, so that an edit to a plugin's
// source recompiles only that source (ServoloopPlugin.cmake). It is part of
// the CMake package, installed beside ServoloopPlugin.cmake, not an API
// header: it spans modules, as a plugin's includes do.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/return_type.hpp"
#include "servoloop/core/time.hpp"
#include "servoloop/hardware_interface/actuator_interfaces.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/hardware_interface/robot_hw.hpp"
#include "servoloop/plugin/plugin_register.hpp"
#include "servoloop/realtime/messages.hpp"
#include "servoloop/realtime/topic_bus.hpp"
