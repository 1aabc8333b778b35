#pragma once
// The physics a simulation backend brings: a joint-space engine that SimRobotHW
// drives. Everything else a backend needs (URDF, transmissions, joint limits,
// command modes, emergency stop, world settings) lives in SimRobotHW, so a new
// backend is one PhysicsEngine plus a three-line RobotHW class.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <urdf_model/model.h>

#include "servoloop/hardware_interface/simulated_world.hpp"
#include "servoloop/sim_common/sim_settings.hpp"

namespace servoloop::sim_common {

// What a joint's command currently means, set by the controller switch.
//   none     — no running controller commands the joint: zero effort is applied
//              (gazebo_ros_control's behaviour for a stopped controller);
//   effort   — the command is an effort (N·m or N);
//   velocity — a velocity target (rad/s or m/s) for the engine's motor;
//   position — a position target (rad or m) for the engine's motor.
enum class JointCommandMode : std::uint8_t { none, effort, velocity, position };

// "none", "effort", "velocity" or "position".
const char* toString(JointCommandMode mode) noexcept;

// What the engine gets for one joint on the next step.
struct AppliedJointCommand {
  JointCommandMode mode = JointCommandMode::none;
  // Effort (N·m or N) for none/effort, velocity target for velocity, position
  // target for position; joint space, after limits, motor limits and the
  // emergency stop.
  double value = 0.0;
};

// One joint's state as the engine reports it (rad or m, rad/s or m/s, N·m or N).
struct EngineJointState {
  double position = 0.0;
  double velocity = 0.0;
  double effort = 0.0;
};

// One joint the engine simulates for SimRobotHW, in joint space.
struct EngineJointConfig {
  std::string name;
  // Bound on the effort the engine's velocity/position motor may use (N·m or
  // N): the smaller of the joint's effort limit and what its actuators can
  // deliver through the transmission; +infinity when neither is given; 0 for
  // an effort limit of 0 (the joint cannot be driven, as with effort commands).
  double motor_effort_limit = std::numeric_limits<double>::infinity();
  // Rotor inertia of the joint's actuators reflected to the joint (n²·J for a
  // reduction n), added to the joint's own inertia (kg·m² or kg). 0: none.
  double reflected_rotor_inertia = 0.0;
  // Position at init and reset (rad or m), at rest.
  double initial_position = 0.0;
};

// Non-real-time. The bound an engine's motor works with: motor_effort_limit
// (+infinity: none), or 0 when it is negative or not a number.
inline double motorEffortBound(const EngineJointConfig& joint) noexcept {
  return joint.motor_effort_limit >= 0.0 ? joint.motor_effort_limit : 0.0;
}

// The root link of a floating robot, ground truth: the pose of its frame in
// the world, and the velocity of that frame's origin and its angular
// velocity, both in world axes.
struct EngineBaseState {
  Eigen::Vector3d position{Eigen::Vector3d::Zero()};                // m
  Eigen::Quaterniond orientation{Eigen::Quaterniond::Identity()};   // root link -> world
  Eigen::Vector3d linear_velocity{Eigen::Vector3d::Zero()};         // m/s, world axes
  Eigen::Vector3d angular_velocity{Eigen::Vector3d::Zero()};        // rad/s, world axes
};

// A URDF link frame's state in the world, ground truth: its pose, the
// velocity of its origin and its angular velocity, both in world axes.
struct EngineLinkState {
  Eigen::Vector3d position{Eigen::Vector3d::Zero()};               // m
  Eigen::Quaterniond orientation{Eigen::Quaterniond::Identity()};  // link -> world
  Eigen::Vector3d linear_velocity{Eigen::Vector3d::Zero()};        // m/s, world axes
  Eigen::Vector3d angular_velocity{Eigen::Vector3d::Zero()};       // rad/s, world axes
};

// The wrench a joint transmits: what the parent link applies to the child
// link through the joint (constraint forces and the joint's actuation alike),
// the torque about the joint origin (the child link frame's origin), both in
// the child link frame's axes. N and N·m.
struct EngineJointWrench {
  Eigen::Vector3d force{Eigen::Vector3d::Zero()};
  Eigen::Vector3d torque{Eigen::Vector3d::Zero()};
};

// One contact point of a link with another body during the last step.
struct EngineContact {
  // The other collision, Gazebo's scoped name "model::link::collision";
  // owned by the engine, valid until the world's bodies change.
  const std::string* other = nullptr;
  Eigen::Vector3d position{Eigen::Vector3d::Zero()};  // m, world frame
  Eigen::Vector3d normal{Eigen::Vector3d::UnitZ()};   // unit, world axes: the normal force's direction on the link
  Eigen::Vector3d force{Eigen::Vector3d::Zero()};     // N, world axes: what the other body applies to the link
  double depth = 0.0;                                 // m of overlap (0: touching)
};

// Threading: init() and reset() are non-real-time (they may allocate and
// throw). Every other method runs on the real-time thread: no allocation, no
// locks, no logging, no exceptions. Joint indices are those of the `joints`
// list given to init() (SimRobotHW's joint order); they are not range-checked.
class PhysicsEngine {
 public:
  virtual ~PhysicsEngine() = default;

  // Non-real-time. A short name for messages, e.g. "bullet".
  virtual const char* name() const noexcept = 0;

  // Non-real-time, before init(): the robot is to be built into `world`
  // (hardware_interface/simulated_world.hpp), which outlives the engine. The
  // default accepts a world whose robots are simulated apart; an engine that
  // shares a world with others overrides it. Throws servoloop::ConfigError
  // for a world it cannot build into.
  virtual void joinWorld(hardware_interface::SimulatedWorld& world);

  // Non-real-time. Builds the world of `model` and places every joint of
  // `joints` at its initial position, at rest. `source_name` names the robot
  // description in errors. Throws servoloop::ConfigError when the model
  // cannot be simulated or a joint of `joints` is not a movable joint of it.
  virtual void init(const urdf::ModelInterface& model, const SimSettings& settings,
                    const std::vector<EngineJointConfig>& joints,
                    const std::string& source_name) = 0;

  // Real-time. Joint state after the last step (rad or m, rad/s or m/s).
  virtual double jointPosition(std::size_t joint) const noexcept = 0;
  virtual double jointVelocity(std::size_t joint) const noexcept = 0;
  // Real-time. The effort the joint's actuators applied during the last step
  // (N·m or N); engine-specific for motor modes (see each backend).
  virtual double jointEffort(std::size_t joint) const noexcept = 0;

  // Real-time. Commands for the next step(). An effort acts for that step
  // only; the motor targets stay in force until another command replaces them.
  virtual void setJointEffort(std::size_t joint, double effort) noexcept = 0;
  virtual void setJointVelocityTarget(std::size_t joint, double velocity) noexcept = 0;
  virtual void setJointPositionTarget(std::size_t joint, double position) noexcept = 0;

  // Real-time. The floating root link's state after the last step; false
  // (out untouched) for a fixed base or an engine that does not track one.
  virtual bool readBaseState(EngineBaseState& /*out*/) const noexcept { return false; }
  // Non-real-time. Teleports the floating root link to `state` (finite, unit
  // quaternion); the joints keep their state. Throws servoloop::Error for a
  // fixed base or an engine that does not track one (the default).
  virtual void setBaseState(const EngineBaseState& state);

  // Sensors. Non-real-time, after init(): whether the engine gives link
  // states and joint wrenches (the methods below). The default: no.
  virtual bool simulatesSensors() const noexcept { return false; }
  // Non-real-time, after init(): follow URDF link `link` (any link of the
  // model, also one fixed to another) for readLinkState; returns the index
  // to read it with. Throws servoloop::ConfigError naming the link when the
  // engine cannot (the default: no sensors).
  virtual std::size_t trackLink(const std::string& link);
  // Real-time. The state of a tracked link after the last step.
  virtual void readLinkState(std::size_t /*tracked*/, EngineLinkState& /*out*/) const noexcept {}
  // Non-real-time, after init(): measure the wrench of URDF joint `joint`
  // (any joint, fixed ones too where the engine keeps them) for
  // readJointWrench; returns the index to read it with. Throws
  // servoloop::ConfigError naming the joint when the engine cannot.
  virtual std::size_t trackJointWrench(const std::string& joint);
  // Real-time. The wrench the tracked joint transmitted during the last step.
  virtual void readJointWrench(std::size_t /*tracked*/, EngineJointWrench& /*out*/) const noexcept {}
  // Non-real-time, after init(): report the contacts of URDF link `link`'s
  // collision geometry for readContacts; returns the index to read them
  // with. Throws servoloop::ConfigError naming the link when the engine
  // cannot.
  virtual std::size_t trackContacts(const std::string& link);
  // Real-time. The tracked link's contact points of the last step, at most
  // out.size() of them written; returns how many there were in all.
  virtual std::size_t readContacts(std::size_t /*tracked*/, std::span<EngineContact> /*out*/) const noexcept {
    return 0;
  }

  // Real-time. Every joint's state at once, `states[j]` for joint j, as the
  // getters above give it; `states` holds one entry per joint of init()'s
  // list. SimRobotHW reads through this each cycle. The default calls the
  // getters; an engine may override it to read all joints in one pass.
  virtual void readJointStates(std::span<EngineJointState> states) const noexcept;
  // Real-time. The commands of every joint for the next step() at once:
  // mode none and effort set the effort, velocity and position the motor
  // target, as the setters above do. The default calls the setters.
  virtual void applyJointCommands(std::span<const AppliedJointCommand> commands) noexcept;

  // Real-time. Advances the world by one settings.time_step_s; in a shared
  // world, only takes the commands (the world's step() advances it).
  virtual void step() noexcept = 0;

  // Non-real-time. Back to the state right after init(): initial positions,
  // at rest, commands cleared.
  virtual void reset() = 0;
  // Non-real-time. Teleports a joint (no dynamics).
  virtual void setJointState(std::size_t joint, double position, double velocity) = 0;
};

// The loops behind readJointStates() and applyJointCommands(), over the
// per-joint calls of `engine`. The defaults use them with PhysicsEngine (one
// virtual call per joint and value); an engine class marked final may
// override the two with `readJointStatesVia(*this, ...)` and
// `applyJointCommandsVia(*this, ...)`, whose calls then bind statically.
template <class Engine>
void readJointStatesVia(const Engine& engine, std::span<EngineJointState> states) noexcept {
  for (std::size_t j = 0; j < states.size(); ++j) {
    states[j] = EngineJointState{engine.jointPosition(j), engine.jointVelocity(j), engine.jointEffort(j)};
  }
}

template <class Engine>
void applyJointCommandsVia(Engine& engine, std::span<const AppliedJointCommand> commands) noexcept {
  for (std::size_t j = 0; j < commands.size(); ++j) {
    const AppliedJointCommand& command = commands[j];
    switch (command.mode) {
      case JointCommandMode::none:
      case JointCommandMode::effort:
        engine.setJointEffort(j, command.value);
        break;
      case JointCommandMode::velocity:
        engine.setJointVelocityTarget(j, command.value);
        break;
      case JointCommandMode::position:
        engine.setJointPositionTarget(j, command.value);
        break;
    }
  }
}

}  // namespace servoloop::sim_common
