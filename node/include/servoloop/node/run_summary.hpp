#pragma once
// What `servoloop launch` reports when a run ends: simulated and wall time,
// the real-time factor achieved, cycles, and per robot its controllers' states,
// final joint positions and loop timing statistics. Non-real-time.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "servoloop/controller_manager/loop_statistics.hpp"
#include "servoloop/node/robot_instance.hpp"

namespace servoloop::node {

struct ControllerSummary {
  std::string name;
  std::string type;
  std::string state;       // "running", "stopped", "initialized", "failed"
  std::string last_fault;  // empty unless it failed at some point
  controller_manager::DurationSnapshot update_time;  // its update() calls (timed cycles)
};

struct RobotSummary {
  std::string robot_namespace;
  std::string backend;
  std::vector<ControllerSummary> controllers;
  std::vector<JointReading> joints;  // final state
  controller_manager::LoopStatisticsSnapshot loop;
  std::vector<std::string> launch_failures;  // see RobotInstance::launchFailures
  // The safety state at the end and how often the robot was stopped.
  std::string safety_state = "running";
  std::string safety_reason;  // empty when running
  std::uint64_t protective_stops = 0;
  std::uint64_t emergency_stops = 0;
  // The run ended with the robot stopped for its hardware: a protective stop
  // (also under an emergency stop) or a fault holds. A --duration run then
  // exits with status 1.
  bool stopped_by_hardware = false;
};

struct RunSummary {
  double sim_time_s = 0.0;         // longest simulated time of any robot
  double wall_time_s = 0.0;        // from Node::start to the end of the run
  double real_time_factor = 0.0;   // sim_time_s / wall_time_s
  std::uint64_t cycles = 0;        // physics steps, all robots
  std::vector<RobotSummary> robots;
};

// {count, min, mean, p50, p99, max} in seconds.
nlohmann::json toJson(const controller_manager::DurationSnapshot& duration);
// A loop's statistics: cycles, times, compute ("cycle"), phases ("read",
// "write"), wake-up latency, period jitter, overruns and errors.
nlohmann::json toJson(const controller_manager::LoopStatisticsSnapshot& loop);

// Captures a robot's part (call with its loop stopped, before its controllers
// are shut down).
RobotSummary summarizeRobot(RobotInstance& robot);

// One JSON object:
// {"sim_time": s, "wall_time": s, "real_time_factor": x, "cycles": n,
//  "robots": [{"namespace", "backend",
//              "controllers": [{"name", "type", "state", "last_fault"?}],
//              "joints": [{"name", "position", "velocity", "effort"}],
//              "loop": {"cycles", "control_updates", "sim_time", "wall_time",
//                       "real_time_factor", "compute": {"min", "mean", "p50",
//                       "p99", "max"} (s), "overruns", "schedule_resets",
//                       "hardware_errors"}}]}
nlohmann::json toJson(const RunSummary& summary);

// Readable text, several lines, ending in a newline.
std::string toText(const RunSummary& summary);

}  // namespace servoloop::node
