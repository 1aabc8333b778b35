#pragma once
// A Bullet (double precision, Featherstone btMultiBody) world built from a URDF
// model, driven in joint space. The Bullet RobotHW backend wraps it; tests use
// it directly. No Bullet type appears here (pimpl).
#include <cstddef>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <urdf_model/model.h>

namespace servoloop::sim_bullet {

enum class FixedBase {
  automatic,  // fixed when the URDF's root link is named "world", floating otherwise
  fixed,
  floating,
};

struct WorldSettings {
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};  // m/s^2, world frame
  double time_step_s{0.001};                 // one solver step per step() call
  bool ground_plane{false};                  // static plane z = 0 (normal +z)
  FixedBase fixed_base{FixedBase::automatic};
  // Collisions between the robot's own links (never between a parent and its
  // child). Off by default, as in Gazebo.
  bool self_collision{false};
  // setJointPositionTarget: the motor drives the position error down with this
  // time constant (first order), as fast as the effort limit allows. >= time_step_s.
  double position_motor_time_constant_s{0.02};
  // Pose of the root link frame in the world at construction and reset();
  // for a root link named "world", where that link (and everything fixed to
  // it) stands, as Gazebo places such a robot at its spawn pose.
  Eigen::Vector3d initial_base_position{Eigen::Vector3d::Zero()};
  Eigen::Quaterniond initial_base_orientation{Eigen::Quaterniond::Identity()};
  // Rotor inertia reflected to a joint (n²·J for a reduction n, kg·m²), by
  // revolute or continuous joint name. Added to the inertia of the joint's
  // child body about the joint axis (a pure rotational inertia, no mass):
  // exactly n²·J more inertia for the joint itself; joints further up the
  // chain whose axes are not perpendicular feel it too (see
  // docs/simulation.md, the bullet section). Prismatic joints are rejected.
  std::map<std::string, double> reflected_rotor_inertia;
  // Contact friction coefficient by link name (sim_common/contact_friction.hpp);
  // links not listed have 1. A contact with the ground plane has the link's.
  std::map<std::string, double> link_friction;
};

enum class JointType { revolute, continuous, prismatic };

// Pose and twist of the root link frame (not its centre of mass), world frame.
struct BaseState {
  Eigen::Vector3d position{Eigen::Vector3d::Zero()};             // m
  Eigen::Quaterniond orientation{Eigen::Quaterniond::Identity()};  // root link -> world
  Eigen::Vector3d linear_velocity{Eigen::Vector3d::Zero()};       // of the root link origin, m/s
  Eigen::Vector3d angular_velocity{Eigen::Vector3d::Zero()};      // rad/s
};

// A URDF link frame: its pose, the velocity of its origin and its angular
// velocity, world frame and axes.
using LinkState = BaseState;

// What a joint transmits from the parent link to the child link (actuation
// and constraint forces), the torque about the joint origin, both in the
// child link frame's axes. N and N m.
struct JointWrench {
  Eigen::Vector3d force{Eigen::Vector3d::Zero()};
  Eigen::Vector3d torque{Eigen::Vector3d::Zero()};
};

// One contact point of a link during the last step, world frame.
struct LinkContact {
  const std::string* other = nullptr;  // the other collision, "robot::link::link_collision" (the scene's)
  Eigen::Vector3d position{Eigen::Vector3d::Zero()};  // m
  Eigen::Vector3d normal{Eigen::Vector3d::UnitZ()};   // the normal force's direction on the link
  Eigen::Vector3d force{Eigen::Vector3d::Zero()};     // N, on the link from the other body
  double depth = 0.0;                                 // m of overlap
};

// The robot's collision geometry that reaches deepest below the ground plane.
struct GroundPenetration {
  std::string link;    // the URDF link whose <collision> it is ("" when none is below)
  double depth_m = 0;  // how far below z = 0 its lowest point is (0 when none is)
};

// Where a robot starts inside another member of its scene.
struct MemberOverlap {
  std::string link;        // the robot's link in contact ("" when it overlaps nothing)
  std::string other;       // what it overlaps: "robot 'box' link 'box'"
  double depth_m = 0.0;    // how deep they overlap (0 when they do not)
};

// Mass properties of one simulated body (a moving link with the links fixed to
// it merged in), in that link's frame. For tests and diagnostics.
struct BodyMassProperties {
  double mass_kg{0.0};
  Eigen::Vector3d com{Eigen::Vector3d::Zero()};        // centre of mass, link frame, m
  Eigen::Matrix3d inertia{Eigen::Matrix3d::Zero()};    // about the COM, link frame axes, kg m^2
};

class BulletScene;  // bullet_scene.hpp

// Joint-space simulation of one URDF robot.
//
// Model: revolute, continuous and prismatic joints become Featherstone joints;
// links attached by fixed joints are merged into their parent (mass, centre of
// mass and inertia combined with the parallel-axis theorem). Floating and
// planar joints are rejected. Collision shapes: box, cylinder (URDF axis z),
// sphere, and meshes as their bounded convex hull (sim_common/collision_mesh.hpp). A link never
// collides with its parent; other links of the robot collide with each other.
//
// Physics is what the URDF says and nothing more: Bullet's default link
// damping is off, its velocity clamp is raised out of reach, <dynamics damping>
// is a viscous joint torque -b*qdot and <dynamics friction> a Coulomb friction
// bounded by `friction` (a velocity motor with target 0), and finite revolute
// and prismatic limits are physical stops. Effort commands are applied as
// given: limiting them is the caller's job (SimRobotHW enforces the URDF and
// YAML limits), so no second, possibly different limit applies here. The
// velocity/position motors are bounded by the joint's motor effort limit,
// <limit effort> unless setJointMotorEffortLimit() says otherwise.
//
// Joint order (indices 0..numJoints()-1): the non-fixed joints depth-first from
// the root link, children of a link in urdfdom's order (sorted by joint name).
//
// Size: at most 1,000 revolute, continuous and prismatic joints (construction
// throws ConfigError beyond): Bullet's multibody solver is dense, so a step's
// memory and time grow with the square of the joint count. Fixed joints are
// not counted (their links are merged), and any depth of tree is built.
//
// Threading: construction throws ConfigError and allocates; after that
// step(), the setters and the getters taking an index do not allocate and are
// real-time safe. Index arguments are not range-checked in release builds.
class BulletWorld {
 public:
  // The robot in a scene of its own (settings' gravity, time step and ground plane).
  BulletWorld(const urdf::ModelInterface& model, const WorldSettings& settings = {});
  // The robot in `scene`, beside the scene's other members, touching them;
  // the scene steps it (step() here does nothing). Throws ConfigError when
  // settings' time step, gravity or ground plane differ from the scene's.
  // `scene` must outlive the robot.
  BulletWorld(const urdf::ModelInterface& model, const WorldSettings& settings, BulletScene& scene);
  ~BulletWorld();
  BulletWorld(const BulletWorld&) = delete;
  BulletWorld& operator=(const BulletWorld&) = delete;

  std::size_t numJoints() const;
  const std::vector<std::string>& jointNames() const;
  // Index of a non-fixed joint; throws servoloop::Error naming the joint if unknown.
  std::size_t jointIndex(const std::string& name) const;
  JointType jointType(std::size_t joint) const;
  // <limit effort> of the joint, or +infinity when the URDF gives none (or 0).
  double jointEffortLimit(std::size_t joint) const;

  double jointPosition(std::size_t joint) const;  // rad or m
  double jointVelocity(std::size_t joint) const;  // rad/s or m/s

  // Bound on the effort of the joint's velocity/position motor (N m or N,
  // >= 0; +infinity: unbounded). Defaults to jointEffortLimit(). Takes effect
  // at once, also for a motor already running. Real-time safe.
  void setJointMotorEffortLimit(std::size_t joint, double limit);
  double jointMotorEffortLimit(std::size_t joint) const;
  // Reflected rotor inertia added to the joint (kg m²), from WorldSettings.
  double jointRotorInertia(std::size_t joint) const;

  // Effort mode: `effort` (N m or N), applied as given (no clamp), acts during
  // the next step() only. Turns off the joint's velocity/position motor.
  void setJointEffort(std::size_t joint, double effort);
  // Motor modes (stay in force until another command): a Bullet joint motor
  // reaching the target as fast as the motor effort limit allows.
  void setJointVelocityTarget(std::size_t joint, double velocity);
  void setJointPositionTarget(std::size_t joint, double position);
  // The effort the joint's actuator applied during the last step (N m or N):
  // the effort command in effort mode; in velocity/position mode the motor's
  // effort, its constraint impulse over the step divided by the time step
  // (within +-jointMotorEffortLimit()). Damping, friction, stops and contacts
  // are not included. 0 before the first step and after reset().
  double jointAppliedEffort(std::size_t joint) const;
  // Teleports the joint (no dynamics); link poses are updated at once.
  void setJointState(std::size_t joint, double position, double velocity);

  // Advances exactly one time step of settings.time_step_s: the robot's own
  // scene; nothing when it shares one (the scene's step() moves it).
  void step();
  double time() const;  // s of steps the robot took since construction or reset()
  double timeStep() const;
  // Back to the initial state: joints at 0 at rest, base at its initial pose at
  // rest, time 0, all commands cleared (effort mode, zero effort).
  void reset();

  bool isFixedBase() const;
  BaseState baseState() const;
  // Teleports a floating base (root link frame); ignored for a fixed base.
  void setBaseState(const BaseState& state);

  // World position of a URDF link frame's origin (any link, merged or not);
  // throws servoloop::Error for an unknown link. Not for the real-time path.
  Eigen::Vector3d linkWorldPosition(const std::string& link_name) const;
  // Sensors. Non-real-time: follow a URDF link frame (any link, merged or
  // not); returns the index for linkState(). Throws servoloop::ConfigError
  // for an unknown link.
  std::size_t trackLink(const std::string& link_name);
  // Non-real-time: measure what a revolute, continuous or prismatic joint
  // transmits (Bullet's joint feedback); returns the index for
  // jointWrench(). Throws ConfigError for any other joint name (a fixed
  // joint's links are merged into one body).
  std::size_t trackJointWrench(const std::string& joint_name);
  // Non-real-time: report the contacts of a URDF link's collision geometry
  // (a link merged into a body: its own shapes only); returns the index for
  // readContacts(). Throws servoloop::ConfigError for an unknown link.
  std::size_t trackContacts(const std::string& link_name);
  // Real-time: the tracked link's state now; the tracked joint's wrench
  // during the last step (zero before the first); the tracked link's
  // contact points of the last step (at most out.size() written, the count
  // of all returned).
  LinkState linkState(std::size_t tracked) const;
  JointWrench jointWrench(std::size_t tracked) const;
  std::size_t readContacts(std::size_t tracked, std::span<LinkContact> out) const;

  // Mass properties of the body that `link_name` moves with, expressed in the
  // frame of that body's first link (the one its joint moves). The URDF's:
  // without the rotor inertia added for the body's joint.
  BodyMassProperties bodyMassProperties(const std::string& link_name) const;

  // In the current pose: the moving link whose collision geometry (margin
  // included) reaches deepest below the ground plane, e.g. a robot spawned
  // with its feet in the floor, which the contacts throw up at the first
  // step. Nothing without a ground plane; a fixed base is not counted (it
  // does not collide with the ground). Not for the real-time path.
  GroundPenetration deepestGroundPenetration() const;

  // In the current pose: the deepest overlap of the robot's collision
  // geometry with another member of its scene (a robot spawned into
  // another, which the contacts throw apart at the first step). Links the
  // robot's own self-collision rules exclude are not counted, nor the
  // ground plane (deepestGroundPenetration). Not for the real-time path.
  MemberOverlap deepestMemberOverlap() const;

  // Checks on Bullet's settings, for tests: true when btScalar is double.
  static bool usesDoublePrecision();
  // Bullet's per-link damping and velocity clamp as configured (0 and a large value).
  double linkLinearDamping() const;
  double linkAngularDamping() const;
  double maxCoordinateVelocity() const;

 private:
  BulletWorld(const urdf::ModelInterface& model, const WorldSettings& settings, BulletScene* scene);

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace servoloop::sim_bullet
