#pragma once
// Simulation parameters read from the robot namespace of the parameter YAML
// (HardwareInfo::parameters), next to joint_limits: and the controllers:
//
//   one_DOF_robot:
//     sim:
//       time_step: 0.001            # s, > 0
//       gravity: [0.0, 0.0, -9.81]  # m/s², world frame
//       ground_plane: false         # static plane z = 0
//       initial_positions:          # rad or m; joints not listed start at 0
//         joint1: 0.5
//       fixed_base: true            # default: fixed when the root link is
//                                   # "world" or has no mass, floating otherwise
//       pose: [0, 0, 0.5, 0, 0, 0]  # root link in the world: x y z (m), roll
//                                   # pitch yaw (rad, fixed axes X, Y, Z)
//       self_collide: false         # default: the URDF's
//                                   # <gazebo><self_collide>, else false (Gazebo's default)
//     actuators:
//       motor1:                     # an actuator of a <transmission>
//         max_effort: 0.2           # motor torque/force limit, actuator space
//         rotor_inertia: 1.0e-4     # kg·m² (kg for linear motors), actuator space
//
// Parsing is non-real-time and throws servoloop::ConfigError naming the key
// (e.g. "/one_DOF_robot/sim/time_step") and what it must be. Unknown keys
// under sim: and actuators/<name>: are logged as warnings and ignored.
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <urdf_model/model.h>
#include <yaml-cpp/yaml.h>

namespace servoloop::sim_common {

// How the robot's root link is held in the world.
enum class BaseMode {
  automatic,  // fixed when the root link is "world" or has no mass (pybullet's static base), else floating
  fixed,      // welded to the world at `pose` (pybullet's useFixedBase)
  floating,   // free in six degrees of freedom
};

struct SimSettings {
  double time_step_s = 0.001;                      // one physics step, s
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};        // m/s², world frame
  bool ground_plane = false;                       // static plane z = 0, normal +z
  std::map<std::string, double> initial_positions;  // joint → rad or m
  BaseMode base = BaseMode::automatic;
  // Pose of the root link frame in the world at start and reset; for a root
  // link named "world", where that link stands (Gazebo's spawn pose).
  Eigen::Vector3d base_position{Eigen::Vector3d::Zero()};
  Eigen::Quaterniond base_orientation{Eigen::Quaterniond::Identity()};
  // Collisions between the robot's own links (parent and child never collide).
  bool self_collide = false;
  // Contact friction coefficient per link, from the URDF's <gazebo reference>
  // <mu1>/<mu2> (contact_friction.hpp); links not listed have 1, Gazebo's default.
  std::map<std::string, double> link_friction;
};

// True when the URDF asks for self-collision the Gazebo way: a
// <gazebo><self_collide>true</self_collide></gazebo> without a reference (the
// whole model). Non-real-time; false for text that is not XML.
bool urdfRequestsSelfCollision(const std::string& urdf_xml);

// Whether the base of `model` is fixed under `mode`: mode fixed; or, with
// mode automatic, a root link named "world" or a root body without mass.
bool isFixedBase(const urdf::ModelInterface& model, BaseMode mode);

// Mass of the rigid body `link` heads: its own and that of the links attached
// below it through fixed joints (Gazebo lumps them into one body), kg.
double rigidBodyMass(const urdf::Link& link);

// Per-actuator parameters, in actuator space (motor side of the transmission).
struct ActuatorParameters {
  // Motor effort limit (N·m or N), applied to the actuator effort command after
  // the joint→actuator transmission map. +infinity: no limit.
  double max_effort = std::numeric_limits<double>::infinity();
  // Rotor inertia (kg·m² or kg); the joint feels it multiplied by the square
  // of the reduction.
  double rotor_inertia = 0.0;
};

// Reads <ns>/sim from `robot_ns` (the map of the robot namespace; may be null
// or lack sim:). `ns` (e.g. "/one_DOF_robot") prefixes key names in messages.
// Throws ConfigError for a value of the wrong type or range, and for an
// initial position naming no movable joint of `model` or lying outside the
// joint's URDF position limits.
// `urdf_self_collide` is the default of self_collide (see
// urdfRequestsSelfCollision).
SimSettings parseSimSettings(const YAML::Node& robot_ns, const urdf::ModelInterface& model,
                             const std::string& ns, bool urdf_self_collide = false);

// Reads <ns>/actuators. Every actuator of `actuator_names` gets an entry (the
// defaults when it is not listed). Throws ConfigError for a bad value and for
// an entry naming an actuator not in `actuator_names` (listing the known ones).
std::map<std::string, ActuatorParameters> parseActuatorParameters(
    const YAML::Node& robot_ns, const std::vector<std::string>& actuator_names,
    const std::string& ns);

}  // namespace servoloop::sim_common
