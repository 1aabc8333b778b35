#pragma once
// A request to start and stop controllers in one step, as ros_control's
// switch_controller service takes it.
#include <cstdint>
#include <string>
#include <vector>

namespace servoloop::controller_manager {

// ros_control's values: BEST_EFFORT = 1, STRICT = 2.
enum class SwitchStrictness : std::uint8_t {
  // Unknown names, stopping a controller that is not running and starting one
  // that is running are dropped from the request.
  BEST_EFFORT = 1,
  // Any of those fails the whole switch.
  STRICT = 2,
};

struct SwitchRequest {
  std::vector<std::string> start_controllers;
  std::vector<std::string> stop_controllers;
  SwitchStrictness strictness = SwitchStrictness::STRICT;
  // Kept for ros_control compatibility. servoloop's hardware switches within
  // the cycle (doSwitch is synchronous), so controllers always start in the
  // cycle the switch is carried out, with or without it.
  bool start_asap = false;
  // How long switchController waits for the real-time thread to carry the
  // switch out, in seconds; 0 waits forever.
  double timeout_s = 0.0;
};

}  // namespace servoloop::controller_manager
