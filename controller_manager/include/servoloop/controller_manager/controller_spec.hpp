#pragma once
// What the manager reports about its controllers: listControllers entries and
// the faults the real-time thread contained.
#include <cstdint>
#include <string>
#include <vector>

#include "servoloop/controller_manager/controller_base.hpp"
#include "servoloop/hardware_interface/controller_info.hpp"

namespace servoloop::controller_manager {

// Why the real-time thread stopped a controller.
enum class FaultKind : std::uint8_t {
  starting_threw,         // starting() threw
  update_threw,           // update() threw
  update_returned_error,  // update() returned ReturnType::error
  non_finite_command,     // a claimed command was NaN or infinite after starting()/update()
  stopping_threw,         // stopping() threw
  hardware_failed,        // the robot's hardware failed (protective stop, safety_supervisor.hpp)
};

const char* toString(FaultKind kind) noexcept;

// One loaded controller, as listControllers reports it.
struct ControllerSpec {
  std::string name;  // e.g. "joint1_position_controller"
  std::string type;  // e.g. "effort_controllers/JointPositionController"
  ControllerState state = ControllerState::initialized;
  // What it claims, one entry per interface it uses.
  std::vector<hardware_interface::InterfaceResources> claimed_resources;
  // The rate it really runs at (a divisor of the manager's rate), in Hz; 0 when
  // the manager runs at no fixed rate (the controller updates every cycle).
  double update_rate_hz = 0.0;
  // It updates every update_divisor-th manager cycle.
  std::uint32_t update_divisor = 1;
  // Why it was last stopped for a fault; empty if it never was.
  std::string last_fault;
  // The kind of that fault (meaningful when last_fault is not empty).
  FaultKind last_fault_kind = FaultKind::update_threw;
};

// A fault the real-time thread contained: the controller was stopped, its
// claimed commands put to safe values, and it was marked failed.
struct ControllerFault {
  std::string controller;
  FaultKind kind = FaultKind::update_threw;
  std::string message;  // the whole sentence, as logged
};

}  // namespace servoloop::controller_manager
