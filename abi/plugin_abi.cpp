// The headers a plugin compiles against. scripts/check_abi.sh compiles this
// file with GCC's class-layout dump and compares the layout and virtual tables
// of every servoloop class it sees with abi/plugin_abi_layout.txt: a plugin
// built against older headers would call the wrong virtual or read the wrong
// member if they changed, so any change needs a kPluginApiVersion bump.
#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/controller_manager/controller_base.hpp"
#include "servoloop/controller_manager/controller_context.hpp"
#include "servoloop/controller_manager/multi_interface_controller.hpp"
#include "servoloop/controllers/common/command_input.hpp"
#include "servoloop/controllers/common/controller_state_publisher.hpp"
#include "servoloop/controllers/pid.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/core/time.hpp"
#include "servoloop/hardware_interface/actuator_interfaces.hpp"
#include "servoloop/hardware_interface/force_torque_sensor_interface.hpp"
#include "servoloop/hardware_interface/hardware_info.hpp"
#include "servoloop/hardware_interface/imu_sensor_interface.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/hardware_interface/joint_limits_interface.hpp"
#include "servoloop/hardware_interface/robot_hw.hpp"
#include "servoloop/hardware_interface/simulated_robot_hw.hpp"
#include "servoloop/plugin/plugin_api.hpp"
#include "servoloop/realtime/action_messages.hpp"
#include "servoloop/realtime/action_registry.hpp"
#include "servoloop/realtime/messages.hpp"
#include "servoloop/realtime/realtime_publisher.hpp"
#include "servoloop/realtime/realtime_subscriber.hpp"
#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/sim_common/physics_engine.hpp"
#include "servoloop/sim_common/sim_robot_hw.hpp"
#include "servoloop/transmissions/robot_transmissions.hpp"
#include "servoloop/transmissions/transmission.hpp"

// Plugins throw servoloop's errors: throwing each here makes the dump list
// their layout even when no header above throws one inline.
[[maybe_unused]] static void throwEachError(int which) {
  if (which == 0) throw servoloop::Error("");
  if (which == 1) throw servoloop::ConfigError("");
  throw servoloop::UnknownHandleError("");
}
