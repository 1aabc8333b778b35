#include "launch_file_keys.hpp"

#include "servoloop/core/time.hpp"

namespace servoloop::node::launch_keys {

using params::Schema;
using params::UnknownKeys;
using params::ValueType;

const Schema& top() {
  static const Schema schema("launch file",
                             {
                                 {"world", ValueType::map, "the simulated world: backend, time step, gravity, ground, pacing"},
                                 {"controller_manager", ValueType::map, "the controller manager's update_rate"},
                                 {"realtime", ValueType::map, "the loop thread's scheduling on real hardware"},
                                 {"robots", ValueType::any, "the robots to start, each with its URDF and controllers"},
                                 {"publish", ValueType::any, "messages published at given simulated times"},
                                 {"record", ValueType::any, "topics recorded to CSV files"},
                                 {"plot", ValueType::any, "plots drawn from the recordings after the run"},
                                 {"ros1_bridge", ValueType::any, "start the ROS 1 bridge with the node"},
                             },
                             UnknownKeys::error);
  return schema;
}

const Schema& world() {
  static const Schema schema(
      "world settings",
      {
          {"backend", ValueType::text, "the physics engine: bullet, mujoco or mock"},
          {"time_step", ValueType::number, "the physics step (s)", {.min = kMinTimeStepS, .max = kMaxTimeStepS}},
          {"gravity", ValueType::number_list, "gravity [x, y, z] (m/s²)"},
          {"ground_plane", ValueType::boolean, "a ground plane at z = 0"},
          {"real_time_factor", ValueType::number, "pacing against the wall clock; 0 runs as fast as possible", {.min = 0.0}},
          {"clock", ValueType::text, "sim (lockstep with the physics) or wall (paced by the wall clock)"},
          {"file", ValueType::text, "an SDFormat world file (.world, .sdf): its models and settings"},
          {"shared", ValueType::boolean, "true: one physics world for all robots (they touch); false: one each"},
      },
      UnknownKeys::error);
  return schema;
}

const Schema& controllerManager() {
  static const Schema schema(
      "controller manager settings",
      {{"update_rate", ValueType::number, "the control loop's rate (Hz)", {.min = 0.0, .min_exclusive = true}}},
      UnknownKeys::error);
  return schema;
}

const Schema& robot() {
  static const Schema schema(
      "robot",
      {
          {"urdf", ValueType::text, "the robot description (URDF or xacro file)", {.required = true}},
          {"model", ValueType::text, "the model's name (default: the URDF's robot name)"},
          {"namespace", ValueType::text, "the robot's ROS namespace (default: /<model>)"},
          {"params", ValueType::any, "parameter files loaded before the controllers"},
          {"controllers", ValueType::any, "controllers loaded and started"},
          {"stopped_controllers", ValueType::any, "controllers loaded but not started"},
          {"fixed_base", ValueType::boolean, "the root link is fixed to the world"},
          {"pose", ValueType::number_list, "the root link's pose [x, y, z(, roll, pitch, yaw)] (m, rad)"},
          {"self_collide", ValueType::boolean, "links of the robot collide with each other"},
          {"xacro_args", ValueType::map, "arguments of a xacro description (name: value)"},
          {"hardware", ValueType::any, "a hardware plugin instead of the simulation: {type: ..., ...}"},
          {"realtime", ValueType::map, "this robot's loop thread's scheduling"},
      },
      UnknownKeys::error);
  return schema;
}

const Schema& realtime() {
  static const Schema schema(
      "real-time settings",
      {
          {"priority", ValueType::integer, "SCHED_FIFO priority of the loop thread", {.min = 1, .max = 99}},
          {"cpu_affinity", ValueType::any, "CPU numbers the loop thread runs on"},
          {"lock_memory", ValueType::boolean, "lock the process's memory (mlockall)"},
      },
      UnknownKeys::error);
  return schema;
}

const Schema& parameterFile() {
  static const Schema schema("parameter file",
                             {
                                 {"file", ValueType::text, "the YAML file to load", {.required = true}},
                                 {"ns", ValueType::text, "the namespace it is loaded under (default: /)"},
                             },
                             UnknownKeys::error);
  return schema;
}

const Schema& publication() {
  static const Schema schema(
      "publication",
      {
          {"topic", ValueType::text, "the topic to publish on", {.required = true}},
          {"type", ValueType::text, "the message type (default: the topic's)"},
          {"value", ValueType::any, "the message, e.g. 1.0 or {data: 1.0}", {.required = true}},
          {"time", ValueType::number, "when, in simulated seconds", {.min = 0.0}},
      },
      UnknownKeys::error);
  return schema;
}

const Schema& recording() {
  static const Schema schema("recording",
                             {
                                 {"topic", ValueType::text, "the topic to record", {.required = true}},
                                 {"file", ValueType::text, "the CSV file written", {.required = true}},
                             },
                             UnknownKeys::error);
  return schema;
}

}  // namespace servoloop::node::launch_keys
