#pragma once
// The MuJoCo engine behind the "mujoco" backend: the URDF turned into MJCF by
// mjcfFromUrdf (servoloop's own writer, not MuJoCo's URDF importer), loaded
// from memory, stepped in joint space through SimRobotHW's PhysicsEngine
// interface.
//
// Integrator: RK4. servoloop robots are open chains whose joint dynamics are
// smooth between the (rare) contact and stop events, and RK4's fourth-order
// error keeps the seed pendulum's energy within 1e-6 J over 10 s at 1 ms
// (tested; its trajectory within 1e-6 rad of a 10 µs reference), where the
// first-order engines (semi-implicit Euler: bullet, MuJoCo's own Euler) swing
// by O(dt). MuJoCo's "implicit" integrator would only pay off for damping far
// beyond URDF values (b·dt/I near 2); at the seed's b·dt/I = 0.003 the
// explicit treatment is exact to O(dt⁴). Joint stops and friction are MuJoCo
// soft constraints with a time constant of 2 steps, which RK4 integrates
// stably.
//
// Commands, with the same meaning as in the bullet backend:
//  - effort: added to the joint's generalized force (qfrc_applied) for the
//    next step only; SimRobotHW has already applied every limit;
//  - velocity target: a joint motor that reaches the target velocity in one
//    step as far as the joint's motor_effort_limit allows;
//  - position target: the same motor, asked for the velocity
//    (target − q)/τ with τ = 20 ms (bullet's position motor time constant):
//    a first-order approach bounded by the motor effort limit.
//  The motor effort is solved per step from the joint-space inverse inertia
//  (mass matrix with armature), the acceleration every other force gives, and
//  the effort bounds, jointly for all motor-driven joints (projected
//  Gauss-Seidel). As in the bullet backend, the bound is motor_effort_limit
//  (URDF effort limit and actuators' max_effort through the transmission),
//  and jointEffort() reports the motor's effort.
//
// Rotor inertia: the reflected n²·J is MuJoCo's joint armature, exact.
//
// In a node's world (MujocoWorld) every robot is built into one MuJoCo model
// with its names prefixed; step() then solves this robot's motors on the
// shared state and the world's step() integrates, so robots touch.
//
// Threading: init() and reset() and setJointState() are non-real-time. The
// getters, setters and step() run on the real-time thread: MuJoCo steps in
// the mjData arena allocated at init, and every scratch buffer is sized there.
#include <array>
#include <map>
#include <span>
#include <memory>
#include <string>
#include <vector>

#include "servoloop/sim_common/stored_command_physics_engine.hpp"

struct mjModel_;
struct mjData_;

namespace servoloop::sim_mujoco {

class MujocoWorld;

class MujocoPhysics final : public sim_common::StoredCommandPhysicsEngine {
 public:
  MujocoPhysics();
  ~MujocoPhysics() override;
  MujocoPhysics(const MujocoPhysics&) = delete;
  MujocoPhysics& operator=(const MujocoPhysics&) = delete;

  // The time constant of the position motor (s), as in the bullet backend.
  static constexpr double kPositionMotorTimeConstant_s = 0.02;

  const char* name() const noexcept override { return "mujoco"; }

  // Non-real-time, before init(): a MujocoWorld is joined (this robot is
  // built into its model and touches the others); any other world that
  // simulates robots apart gets a model of this robot's own.
  void joinWorld(hardware_interface::SimulatedWorld& world) override;

  // Non-real-time. Throws ConfigError naming `source_name` when the URDF
  // cannot be mapped or MuJoCo refuses the generated model (its message is
  // included), or when a joint of `joints` is not a movable joint.
  void init(const urdf::ModelInterface& model, const sim_common::SimSettings& settings,
            const std::vector<sim_common::EngineJointConfig>& joints, const std::string& source_name) override;

  double jointPosition(std::size_t joint) const noexcept override;
  bool readBaseState(sim_common::EngineBaseState& out) const noexcept override;
  void setBaseState(const sim_common::EngineBaseState& state) override;
  double jointVelocity(std::size_t joint) const noexcept override;
  // The effort applied during the last step: the effort command in effort
  // mode, the motor's effort in velocity/position mode.
  double jointEffort(std::size_t joint) const noexcept override { return joints_[joint].applied_effort; }

  void step() noexcept override;

  // Sensors: any URDF link's frame (bodies are link frames); the wrench of
  // any joint, fixed ones too (MuJoCo keeps a body per link), from the
  // step's own forward pass (mj_rnePostConstraint's interaction forces).
  bool simulatesSensors() const noexcept override { return true; }
  std::size_t trackLink(const std::string& link) override;
  void readLinkState(std::size_t tracked, sim_common::EngineLinkState& out) const noexcept override;
  std::size_t trackJointWrench(const std::string& joint) override;
  void readJointWrench(std::size_t tracked, sim_common::EngineJointWrench& out) const noexcept override;
  std::size_t trackContacts(const std::string& link) override;
  std::size_t readContacts(std::size_t tracked, std::span<sim_common::EngineContact> out) const noexcept override;
  // Real-time: whether a step must give this robot's sensors their data
  // (model_step.hpp), and the capture of its joint wrenches and contacts
  // from the forward pass of the step being taken.
  bool hasSensors() const noexcept {
    return !tracked_link_names_.empty() || !tracked_joint_links_.empty() || !contact_sensors_.empty();
  }
  void captureSensorData() noexcept;

  void reset() override;
  void setJointState(std::size_t joint, double position, double velocity) override;

  // --- inspection (tests, diagnostics) -----------------------------------
  // Simulated time since init or reset (s). Real-time safe.
  double time() const noexcept;
  // World position of a URDF link frame's origin (the root link "world" of a
  // fixed base is the world frame). Non-real-time; throws servoloop::Error
  // for an unknown link.
  std::array<double, 3> linkWorldPosition(const std::string& link_name) const;
  // Number of contacts in the last step's collision detection.
  int contactCount() const noexcept;
  // The MJCF text MuJoCo compiled (empty before init).
  const std::string& mjcf() const noexcept { return mjcf_; }
  // MuJoCo's model and data (null before init): the world's in a shared world.
  const mjModel_* mujocoModel() const noexcept { return m_; }
  const mjData_* mujocoData() const noexcept { return d_; }

  // Non-real-time, no step running (MujocoWorld, after it compiled a model):
  // this robot's joints found again in `model`, whose `data` holds its state.
  void bind(mjModel_* model, mjData_* data);
  // Before every name of the robot in a shared world's model ("" alone).
  const std::string& namePrefix() const noexcept { return prefix_; }

 private:
  struct ModelDeleter {
    void operator()(mjModel_* model) const noexcept;
  };
  struct DataDeleter {
    void operator()(mjData_* data) const noexcept;
  };
  struct Joint {
    int qpos_address = 0;
    int dof_address = 0;
    double motor_effort_limit = 0.0;  // N·m or N, +inf: unbounded
    double applied_effort = 0.0;      // during the last step
  };

  void warnOfGroundPenetration(const urdf::ModelInterface& model, const sim_common::SimSettings& settings,
                               const std::string& source_name) const;
  void placeAtInitialPositions();
  // In a shared world: one warning when the robot starts inside another's body.
  void warnOfOverlap(const std::string& source_name) const;
  // Body ids of the tracked links and joints' child links in the current
  // model, and every body's scoped collision name for contact sensors.
  void bindSensors();
  // The step's contacts of each contact sensor's link (captureSensorData).
  void captureContacts() noexcept;
  // Sets the efforts of the first `motors` entries of motor_joints_.
  void solveMotorEfforts(std::size_t motors) noexcept;

  // A joint of the robot in the model: where its state lies.
  struct OwnJoint {
    int qpos_address;
    int qpos_count;
    int dof_address;
    int dof_count;
  };

  // A robot alone owns its model and data; in a world they are the world's.
  std::unique_ptr<mjModel_, ModelDeleter> model_;
  std::unique_ptr<mjData_, DataDeleter> data_;
  mjModel_* m_ = nullptr;
  mjData_* d_ = nullptr;
  MujocoWorld* world_ = nullptr;
  std::string prefix_;                    // before the robot's names in a shared world
  std::vector<std::string> joint_names_;  // init()'s joints, in order
  std::string base_joint_name_;           // the root's free joint, if it floats
  std::vector<OwnJoint> own_joints_;      // every joint of the robot (free joint too)
  std::string mjcf_;
  int base_qpos_address_ = -1;  // the root's free joint; -1 for a fixed base
  int base_dof_address_ = -1;
  std::vector<Joint> joints_;
  std::vector<double> initial_positions_;
  std::vector<double> motor_limits_;      // per joint of init()
  double position_motor_time_constant_s_ = kPositionMotorTimeConstant_s;

  // Sensors, by URDF name (resolved again whenever the model is recompiled).
  std::map<std::string, std::string> joint_child_links_;  // every URDF joint's child link
  std::vector<std::string> tracked_link_names_;
  std::vector<int> tracked_link_bodies_;
  std::vector<std::string> tracked_joint_links_;  // child link of each tracked joint
  std::vector<int> tracked_joint_bodies_;
  std::vector<sim_common::EngineJointWrench> joint_wrenches_;
  struct ContactSensor {
    std::string link;
    int body = 0;
    std::vector<sim_common::EngineContact> contacts;  // the last step's, capacity fixed
    std::size_t count = 0;                           // all of them (may exceed the capacity)
  };
  std::vector<ContactSensor> contact_sensors_;
  std::string robot_name_;                      // the URDF's, for scoped collision names
  std::vector<std::string> body_collision_names_;  // by body id: "robot::link::link_collision"

  // Motor solve scratch, sized at init for every joint being a motor.
  std::vector<std::size_t> motor_joints_;
  std::vector<double> unit_forces_;        // motors × nv
  std::vector<double> inverse_inertia_;    // motors × nv: columns of M⁻¹
  std::vector<double> wanted_accel_;       // per motor
  std::vector<double> motor_efforts_;      // per motor
};

}  // namespace servoloop::sim_mujoco
