#pragma once
// A servoloop launch file: the world (simulation backend and its settings),
// the robots to spawn into it, a script of timed publications and what to
// record. The YAML form is documented in docs/launch_files.md:
//
//   world: {backend: bullet, time_step: 0.001, gravity: [0, 0, -9.81], ground_plane: false}
//   controller_manager: {update_rate: 1000}
//   robots:
//     - urdf: minimal_robot_description_w_jnt_ctl.urdf
//       model: one_DOF_robot
//       params: [control_config/one_dof_ctl_params.yaml]
//       controllers: [joint_state_controller, joint1_position_controller]
//   publish: [{topic: /one_DOF_robot/joint1_position_controller/command, value: 1.0, time: 0.5}]
//   record: [{topic: /one_DOF_robot/joint_states, file: joint_states.csv}]
//   plot: one_dof.png
//
// Paths in the file are relative to the file's folder. Everything here is
// non-real-time; errors are servoloop::ConfigError naming the launch file, the
// line, the key and the fix.
#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "servoloop/node/realtime_settings.hpp"

namespace servoloop::node {

// The simulated world every robot of the launch file is spawned into.
struct WorldSettings {
  std::string backend = "bullet";  // plugin type name of kind robot_hw
  double time_step_s = 0.001;      // physics step, s
  std::array<double, 3> gravity{0.0, 0.0, -9.81};  // m/s², world frame
  bool ground_plane = false;
  // Simulated seconds per wall second; unset: 0 with a --duration, 1 without.
  std::optional<double> real_time_factor;
  // world.clock: wall (or `launch --clock wall`): simulated robots run on the
  // wall clock like hardware (WallClockLoop, stepped once per cycle); sim
  // (default): in lockstep with their physics (SimulationLoop).
  bool wall_clock = false;
  // world.shared: false simulates each robot in a world of its own (they do
  // not touch), as a backend without a shared world does; for robots that
  // never touch, when that is faster (docs/benchmarks.md).
  bool shared = true;
};

struct ControllerManagerSettings {
  // Rate of ControllerManager::update in Hz; 0: one update per physics step.
  double update_rate_hz = 0.0;
};

// A rosparam-style YAML file and the namespace it is loaded into (as
// roslaunch's <rosparam file=... ns=...>).
struct ParameterFile {
  std::filesystem::path file;  // absolute; empty: the YAML text below
  std::string ns = "/";        // absolute; "/" loads the file unchanged
  std::string yaml;            // inline YAML (a ROS launch file's <param value> or <rosparam> text)
  std::string source_name;     // where the inline YAML comes from, for errors ("x.launch:12")
};

// One robot to spawn.
struct RobotSpec {
  std::filesystem::path urdf;  // absolute; a .xacro file is expanded with xacro_args
  // The URDF's text, when given, is read instead of `urdf` (which then only
  // names where it came from: an SDF world's model).
  std::string description;
  std::map<std::string, std::string> xacro_args;
  std::string model;           // model name; "" = the URDF's robot name
  std::string robot_namespace; // "" = not given (see robot_namespace.hpp)
  std::vector<ParameterFile> params;
  std::vector<std::string> controllers;          // loaded and started
  std::vector<std::string> stopped_controllers;  // loaded only
  // Written into <namespace>/sim/ when given (sim_settings.hpp): fixed_base,
  // pose [x, y, z, roll, pitch, yaw] (m, rad) and self_collide.
  std::optional<bool> fixed_base;
  std::optional<std::array<double, 6>> pose;
  std::optional<bool> self_collide;
  // `hardware: {type: <plugin type>, ...}`: a hardware plugin (kind robot_hw)
  // drives this robot instead of the world's simulation backend, on the wall
  // clock at the manager's update rate. The other keys are the plugin's
  // parameters, loaded under <namespace>/hardware (HardwareInfo::parameters).
  std::string hardware_type;         // "" = simulated by the world's backend
  std::string hardware_params_yaml;  // the mapping without `type`, as YAML text
  std::string hardware_source;       // "launch.yaml:12", for errors in it
  // The robot's own `realtime:` settings; unset: the launch file's.
  std::optional<RealtimeSettings> realtime;
};

// A message published once, at simulated time time_s.
struct TimedPublication {
  std::string topic;
  std::string type = "std_msgs/Float64";
  nlohmann::json message;  // JSON form (message_json.hpp), checked against type
  double time_s = 0.0;
  // No type was given: the node publishes with the type the topic already
  // carries (its controller's command type), else std_msgs/Float64 (or
  // Float64MultiArray for [a, b]), and checks the message against it then.
  bool type_inferred = false;
  std::string origin;  // where it was written (a --pub flag, a launch file's key), for errors
};

// A topic recorded to CSV.
struct RecordSpec {
  std::string topic;
  std::filesystem::path file;  // absolute
};

struct LaunchFile {
  std::filesystem::path source;  // the launch file itself ("" when parsed from text)
  WorldSettings world;
  ControllerManagerSettings controller_manager;
  RealtimeSettings realtime;  // `realtime:` for every robot's loop thread (realtime_settings.hpp)
  std::vector<RobotSpec> robots;
  std::vector<TimedPublication> publish;
  std::vector<RecordSpec> record;
  std::filesystem::path plot;  // absolute; empty: no plot
  bool ros1_bridge = false;    // start `servoloop ros1-bridge` for each robot (docs/ros1.md)
};

// Reads and checks a launch file. Throws ConfigError if it cannot be read, is
// not YAML, has an unknown key, a value of the wrong type or range, or names a
// URDF or parameter file that does not exist.
// A ROS launch file (.launch, roslaunch XML) is read by loadRoslaunchFile
// (roslaunch_xml.hpp) with `roslaunch_args` as its name:=value arguments; a
// YAML launch file takes none (ConfigError if some are given).
LaunchFile loadLaunchFile(const std::filesystem::path& path,
                          const std::map<std::string, std::string>& roslaunch_args = {});

// The same for YAML text; relative paths resolve against base_directory and
// errors name source_name.
LaunchFile parseLaunchFile(std::string_view yaml, std::string_view source_name,
                           const std::filesystem::path& base_directory);

// A timed publication of `value` as `type`. Throws servoloop::Error naming
// `where` when the type is unknown or the value does not fit it. With no type,
// a number is a std_msgs/Float64 and a list a std_msgs/Float64MultiArray; a
// message with fields ({joint_names: ..., points: ...}) is checked later,
// when withTopicType types it as its topic.
TimedPublication makeTimedPublication(std::string topic, std::string type, const nlohmann::json& value,
                                      double time_s, std::string_view where);

// A message with fields given without a type, typed as its topic already
// carries (`topic_type`, e.g. a trajectory controller's command topic), or as
// std_msgs/Float64 when the topic carries nothing yet (""); then checked as
// makeTimedPublication does. A typed publication comes back as it is.
TimedPublication withTopicType(const TimedPublication& publication, std::string_view topic_type);

// "TOPIC[:TYPE]:=VALUE[@TIME]" (the --pub flag). VALUE is YAML (1.0, [1, 2], {data: 1});
// TIME in simulated seconds, default 0. Relative paths: none. Throws
// servoloop::Error naming the flag and the expected form.
TimedPublication parsePubFlag(std::string_view text);

// "TOPIC=FILE.csv" (the --record flag); a relative FILE resolves against the
// current directory. Throws servoloop::Error naming the flag and the expected form.
RecordSpec parseRecordFlag(std::string_view text);

}  // namespace servoloop::node
