#pragma once
#include <vector>

#include "servoloop/hardware_interface/controller_info.hpp"
#include "servoloop/hardware_interface/interface_manager.hpp"
#include "servoloop/core/return_type.hpp"
#include "servoloop/core/time.hpp"

namespace servoloop::hardware_interface {

struct HardwareInfo;  // hardware_info.hpp: what init() is given

// A robot's hardware as controllers see it: a set of interfaces plus the
// read/write calls of the control cycle. Subclasses (real hardware, simulators,
// the mock) register their interfaces in init().
class RobotHW : public InterfaceManager {
 public:
  // Backends are plugins of this kind (see the plugin loader).
  static constexpr const char* kPluginKind = "robot_hw";

  virtual ~RobotHW() = default;

  // Non-real-time. Configures the hardware and registers its interfaces.
  // Throws servoloop::ConfigError naming the file/element at fault.
  virtual void init(const HardwareInfo& info) = 0;

  // Real-time. Reads the hardware's state into the handles' storage.
  virtual ReturnType read(Time time, Duration period) = 0;
  // Real-time. Sends the handles' commands to the hardware.
  virtual ReturnType write(Time time, Duration period) = 0;

  // Non-real-time. True if the controllers that would be running after a
  // switch claim some resource twice. The default rule: a resource claimed by
  // more than one controller (through any claiming interface) is a conflict.
  virtual bool checkForConflict(const std::vector<ControllerInfo>& running) const;

  // Non-real-time. May refuse a switch the hardware cannot carry out.
  virtual bool prepareSwitch(const std::vector<ControllerInfo>& start_list,
                             const std::vector<ControllerInfo>& stop_list);

  // Real-time, fast. Carries out a switch prepareSwitch accepted: puts the
  // joints of start_list's claims into the modes they ask for. The manager
  // calls it before any controller stops or starts; ReturnType::error (or a
  // throw, which it must not) says the hardware could not change its modes,
  // and the manager then aborts the whole switch: nothing stops or starts,
  // the running controllers run on, and the switch request fails naming it.
  // The hardware should then be in the modes it had before.
  virtual ReturnType doSwitch(const std::vector<ControllerInfo>& start_list,
                              const std::vector<ControllerInfo>& stop_list);

  // Real-time, fast, must not throw. True while the hardware's own
  // emergency-stop input (a button, a safety relay, a drive's STO line) is
  // active. The loop polls it after every read(); while it is true the robot
  // is in emergency stop, and a release (`servoloop control estop off`) is
  // refused. The default: no such input.
  virtual bool emergencyStopInput() const noexcept { return false; }
};

}  // namespace servoloop::hardware_interface
