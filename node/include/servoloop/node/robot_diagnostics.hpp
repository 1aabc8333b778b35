#pragma once
// A robot's health as ROS's diagnostics: what `<ns>/diagnostics`
// (diagnostic_msgs/DiagnosticArray) carries once a second of wall time.
// Non-real-time: built from the loop's statistics snapshot, the manager's
// controller list and update times, and the safety state.
#include "servoloop/realtime/messages.hpp"

namespace servoloop::node {

class RobotInstance;

// Statuses:
//   "<ns>: control loop"  OK; WARN when cycles overran since the last report;
//                         ERROR in protective stop, emergency stop or fault.
//                         Values: safety state, cycles, overruns, hardware
//                         errors, real-time factor, and for the cycle, read,
//                         write, wake-up latency and period jitter their
//                         p50/p99/max in microseconds.
//   "<ns>: <controller>"  OK when running, WARN stopped or initialised, ERROR
//                         failed (the message says why); its update() p50/p99/max.
// previous_overruns: the overrun count of the last report (updated).
diagnostic_msgs::DiagnosticArray robotDiagnostics(RobotInstance& robot, std::uint64_t* previous_overruns);

}  // namespace servoloop::node
