#pragma once
// FirstOrderRobotHW: the "first_order" backend as servoloop loads it (a
// robot_hw plugin). All of it but the physics comes from
// servoloop::sim_common::SimRobotHW: URDF parsing, transmissions (implicit
// ones for joints without), joint limits, motor limits, command modes set by
// the controller switch, emergency stop, sim/ world settings, reset. This
// class only adds the backend's own parameters:
//
//   <robot ns>:
//     first_order:
//       time_constant: 0.05   # s, > 0: how fast each joint follows its command
//       damping: 1.0          # N·m·s/rad, > 0: effort mode settles at effort / damping
//
// Threading: as SimRobotHW. init() is non-real-time and throws
// servoloop::ConfigError naming the key at fault; read(), write(), step(),
// doSwitch() and setEmergencyStop() run on the real-time thread.
#include <string>

#include <yaml-cpp/yaml.h>

#include "my_backends/first_order_physics.hpp"
#include "servoloop/sim_common/sim_robot_hw.hpp"

namespace my_backends {

// Reads <ns>/first_order from `robot_ns` (the robot namespace's map; may be
// null or lack first_order:). `ns` (e.g. "/one_DOF_robot") prefixes key names
// in messages. Throws servoloop::ConfigError for a value that is not a
// positive finite number; unknown keys are logged and ignored.
FirstOrderParameters parseFirstOrderParameters(const YAML::Node& robot_ns, const std::string& ns);

class FirstOrderRobotHW final : public servoloop::sim_common::SimRobotHW {
 public:
  // Plugins are default-constructed; configuration happens in init().
  FirstOrderRobotHW();

  // Non-real-time. Reads <ns>/first_order into the engine, then does
  // everything SimRobotHW::init does (which builds the engine's world).
  void init(const servoloop::hardware_interface::HardwareInfo& info) override;

  const FirstOrderParameters& parameters() const noexcept { return physics_->parameters(); }

 private:
  // `physics` is newly allocated; SimRobotHW takes ownership, this class keeps
  // a non-owning pointer to configure it.
  explicit FirstOrderRobotHW(FirstOrderPhysics* physics);

  FirstOrderPhysics* physics_;
};

}  // namespace my_backends
