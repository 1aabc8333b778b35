#include "servoloop/sim_bullet/bullet_world.hpp"

#include "servoloop/sim_bullet/bullet_scene.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <type_traits>

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btEmptyShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyGearConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <btBulletCollisionCommon.h>

#include "body_sensors.hpp"
#include "body_tree.hpp"
#include "overlap_probe.hpp"
#include "bullet_scene_core.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/sim_common/collision_mesh.hpp"
#include "servoloop/sim_common/contact_friction.hpp"
#include "servoloop/sim_common/wheel_contact.hpp"

static_assert(std::is_same_v<btScalar, double>,
              "sim_bullet needs Bullet in double precision (the -float64 libraries and BT_USE_DOUBLE_PRECISION)");

namespace servoloop::sim_bullet {
namespace {

// Bullet clamps joint velocities to 100 by default; this is far above any
// physical robot while still finite for the solver.
constexpr double kMaxCoordinateVelocity = 1e6;
// Impulse bounds (N s or N m s per step) for the stops and for contacts: large
// enough never to be the active limit, so stops and contacts behave as rigid.
constexpr double kRigidConstraintImpulse = 1e8;
// Effort bound of a motor on a joint with no <limit effort>.
constexpr double kUnlimitedMotorEffort = 1e9;
// Share of a mimic joint's position error (q_m − multiplier·q_l − offset) the
// gear constraint removes per step; its velocity row holds the rates exact.
constexpr double kMimicErrorReduction = 0.2;
// Convex hulls get Bullet's margin outside the hull; keep it at 1 mm.
constexpr double kMeshCollisionMargin = 0.001;
// Revolute, continuous and prismatic joints one robot may have. Bullet's
// multibody solver is dense: the constraint row of each joint's motor, stop
// and friction spans every degree of freedom of the robot, so a step needs
// memory and time that grow with the square of the joint count (at 1,000
// joints some 50 MB and 3·10^8 operations a step; at 20,000, over 10 GB and
// tens of seconds a step). A larger robot is refused up front instead.
constexpr std::size_t kMaxMovableJoints = 1000;
btVector3 toBt(const Eigen::Vector3d& v) { return btVector3(v.x(), v.y(), v.z()); }
Eigen::Vector3d toEigen(const btVector3& v) { return Eigen::Vector3d(v.x(), v.y(), v.z()); }
btQuaternion toBt(const Eigen::Quaterniond& q) { return btQuaternion(q.x(), q.y(), q.z(), q.w()); }
Eigen::Quaterniond toEigen(const btQuaternion& q) { return Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()); }
btTransform toBt(const Eigen::Isometry3d& t) {
  return btTransform(toBt(Eigen::Quaterniond(t.linear()).normalized()), toBt(Eigen::Vector3d(t.translation())));
}
Eigen::Isometry3d toEigen(const btTransform& t) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = toEigen(t.getRotation()).toRotationMatrix();
  out.translation() = toEigen(t.getOrigin());
  return out;
}

enum class CommandMode { effort, velocity, position };

struct JointData {
  std::string name;
  JointType type{JointType::revolute};
  double effort_limit{std::numeric_limits<double>::infinity()};        // URDF <limit effort>
  double motor_effort_limit{std::numeric_limits<double>::infinity()};  // bounds command_motor
  double rotor_inertia{0.0};  // reflected n²J added to the child body about the axis, kg m²
  double damping{0.0};   // N m s/rad or N s/m
  double pending_effort{0.0};
  double applied_effort{0.0};  // during the last step (see jointAppliedEffort)
  CommandMode mode{CommandMode::effort};
  btMultiBodyJointMotor* command_motor{nullptr};   // owned by Impl::constraints
  btMultiBodyJointMotor* friction_motor{nullptr};  // null without <dynamics friction>
};

}  // namespace

struct BulletWorld::Impl final : detail::SceneMember {
  WorldSettings settings;
  detail::BodyTree tree;
  bool fixed_base{false};
  Eigen::Isometry3d initial_root_pose{Eigen::Isometry3d::Identity()};
  std::uint64_t steps{0};

  std::vector<JointData> joints;
  std::vector<std::string> joint_names;

  // The scene the robot is built into: its own (own_scene) or a shared one.
  std::unique_ptr<BulletScene> own_scene;
  detail::SceneCore* scene{nullptr};
  btMultiBodyDynamicsWorld* world{nullptr};  // the scene's
  bool joined{false};                        // in scene->members
  std::string robot_name;                    // the URDF's, for messages

  // Bullet objects, removed from the world and destroyed in reverse order of creation (see ~Impl).
  std::unique_ptr<btMultiBody> body;
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders;
  // Per collider, the URDF link of each child of its compound shape.
  std::vector<std::vector<std::string>> collider_child_links;
  std::vector<std::unique_ptr<btMultiBodyConstraint>> constraints;
  // Per-child friction of colliders whose merged links differ (shapeFriction).
  std::vector<std::unique_ptr<std::vector<double>>> child_friction;

  detail::BodySensors sensors;

  // Scratch for forward kinematics after a teleport, sized once.
  btAlignedObjectArray<btQuaternion> scratch_rotations;
  btAlignedObjectArray<btVector3> scratch_origins;

  ~Impl() override {
    if (joined) std::erase(scene->members, this);
    if (world) {
      for (auto& c : constraints) world->removeMultiBodyConstraint(c.get());
      for (auto& c : colliders) {
        scene->collider_owners.erase(c.get());
        world->removeCollisionObject(c.get());
      }
      if (body) world->removeMultiBody(body.get());
    }
  }

  // --- as a member of its scene --------------------------------------------

  // Viscous damping -b*qdot from the velocity at the start of the step. With
  // Bullet's semi-implicit Euler the velocity decays by (1 - b*dt/I) per step:
  // stable for b*dt/I < 2 (the seed joint: 1 * 0.001 / 0.35 = 0.003).
  void beforeSceneStep() noexcept override {
    btMultiBody& mb = *body;
    for (std::size_t j = 0; j < joints.size(); ++j) {
      JointData& joint = joints[j];
      const double damping_effort = -joint.damping * mb.getJointVel(int(j));
      mb.addJointTorque(int(j), joint.pending_effort + damping_effort);
    }
  }

  // What each joint's actuator applied: a motor's effort is its constraint
  // impulse of this step (the solver writes it back per constraint row) over dt.
  void afterSceneStep() noexcept override {
    body->clearForcesAndTorques();
    for (JointData& joint : joints) {
      if (joint.mode == CommandMode::effort) {
        joint.applied_effort = joint.pending_effort;
      } else {
        joint.applied_effort = joint.command_motor->getAppliedImpulse(0) / settings.time_step_s;
      }
      joint.pending_effort = 0.0;
    }
    sensors.afterStep(*body, *world->getDispatcher(), settings.time_step_s, world->getGravity());
    ++steps;
  }

  // Back to the initial state: joints at 0 at rest, base at its initial pose, time 0.
  void resetMember() {
    btMultiBody& mb = *body;
    for (std::size_t j = 0; j < joints.size(); ++j) {
      mb.setJointPos(int(j), 0.0);
      mb.setJointVel(int(j), 0.0);
      setMode(joints[j], CommandMode::effort);
      joints[j].pending_effort = 0.0;
      joints[j].applied_effort = 0.0;
    }
    mb.setBaseWorldTransform(toBt(initial_root_pose * tree.bodies.front().principal_in_link));
    mb.setBaseVel(btVector3(0, 0, 0));
    mb.setBaseOmega(btVector3(0, 0, 0));
    mb.clearForcesAndTorques();
    steps = 0;
    updateKinematics();
  }

  // --- construction -------------------------------------------------------

  // The robot's own scene, or `shared` when it shares one: then the world
  // settings the scene decides must be the robot's too.
  void useScene(const urdf::ModelInterface& model, BulletScene* shared) {
    if (shared == nullptr) {
      own_scene = std::make_unique<BulletScene>(
          SceneSettings{settings.gravity, settings.time_step_s, settings.ground_plane});
      scene = &own_scene->core();
    } else {
      scene = &shared->core();
      const SceneSettings& world_settings = scene->settings;
      const std::string robot = "robot '" + model.getName() + "'";
      const std::string shared_settings =
          "; the robots and objects of one world share its time step, gravity and ground plane";
      if (settings.time_step_s != world_settings.time_step_s) {
        throw ConfigError(robot + " asks for a time step of " + std::to_string(settings.time_step_s) +
                          " s, but its world steps " + std::to_string(world_settings.time_step_s) + " s" +
                          shared_settings);
      }
      if (settings.gravity != world_settings.gravity) {
        throw ConfigError(robot + " asks for another gravity than its world's" + shared_settings);
      }
      if (settings.ground_plane != world_settings.ground_plane) {
        throw ConfigError(robot + (settings.ground_plane ? " asks for a ground plane, but its world has none"
                                                          : " asks for no ground plane, but its world has one") +
                          shared_settings);
      }
    }
    world = scene->world.get();
  }

  void decideBase(const urdf::ModelInterface& model) {
    const bool root_is_world = model.getRoot()->name == "world";
    switch (settings.fixed_base) {
      case FixedBase::automatic: fixed_base = root_is_world; break;
      case FixedBase::fixed: fixed_base = true; break;
      case FixedBase::floating: fixed_base = false; break;
    }
    // A robot fixed to a "world" link stands where it is spawned, as in
    // Gazebo: the world link is placed at the spawn pose.
    initial_root_pose.linear() = settings.initial_base_orientation.normalized().toRotationMatrix();
    initial_root_pose.translation() = settings.initial_base_position;
    const detail::Body& root = tree.bodies.front();
    if (!fixed_base && !(root.mass_kg > 0.0)) {
      throw ConfigError("robot '" + model.getName() + "': root link '" + root.link_name +
                        "' has no mass but the base is floating; give it an <inertial> or attach it to a "
                        "'world' link with a fixed joint");
    }
  }

  void createMultiBody() {
    const int num_links = static_cast<int>(tree.bodies.size()) - 1;
    const detail::Body& root = tree.bodies.front();
    // A fixed base never moves, so its mass only has to be a valid number.
    const bool massless_fixed_root = fixed_base && !(root.mass_kg > 0.0);
    const double base_mass = massless_fixed_root ? 1.0 : root.mass_kg;
    const btVector3 base_inertia = massless_fixed_root ? btVector3(1, 1, 1) : toBt(root.principal_moments);
    body = std::make_unique<btMultiBody>(num_links, base_mass, base_inertia, fixed_base, /*canSleep=*/false);
    body->setBaseWorldTransform(toBt(initial_root_pose * root.principal_in_link));

    for (int link = 0; link < num_links; ++link) setupLink(link);

    // Bullet's hidden defaults off: no artificial damping, no velocity clamp.
    body->setLinearDamping(0.0);
    body->setAngularDamping(0.0);
    body->setMaxCoordinateVelocity(kMaxCoordinateVelocity);
    body->setMaxAppliedImpulse(kRigidConstraintImpulse);
    body->setUseGyroTerm(true);
    // Parent/child pairs stay excluded either way (disableParentCollision).
    body->setHasSelfCollision(settings.self_collision);
    body->finalizeMultiDof();
    world->addMultiBody(body.get());
  }

  void setupLink(int link) {
    const detail::Body& child = tree.bodies[link + 1];
    const detail::Body& parent = tree.bodies[child.parent_body];
    const urdf::Joint& joint = *child.joint;

    // Frames as Bullet wants them: everything relative to the principal
    // (centre of mass) frames of parent and child.
    const Eigen::Isometry3d joint_in_parent_com = parent.principal_in_link.inverse() * child.joint_in_parent_link;
    const Eigen::Isometry3d link_in_child_com = child.principal_in_link.inverse();
    // Rotates parent-frame vectors into the child frame at q = 0 (joint frame = child link frame).
    const Eigen::Matrix3d parent_to_child = link_in_child_com.linear() * joint_in_parent_com.linear().transpose();
    const Eigen::Vector3d axis_in_joint(joint.axis.x, joint.axis.y, joint.axis.z);
    const Eigen::Vector3d axis_in_child_com = (link_in_child_com.linear() * axis_in_joint).normalized();
    const btVector3 parent_com_to_pivot = toBt(Eigen::Vector3d(joint_in_parent_com.translation()));  // parent frame
    const btVector3 pivot_to_child_com = toBt(Eigen::Vector3d(-link_in_child_com.translation()));  // child frame
    const btQuaternion rot_parent_to_child = toBt(Eigen::Quaterniond(parent_to_child).normalized());
    const int parent_link = child.parent_body - 1;

    JointData data;
    data.name = joint.name;
    if (joint.type == urdf::Joint::PRISMATIC) {
      data.type = JointType::prismatic;
      body->setupPrismatic(link, child.mass_kg, toBt(child.principal_moments), parent_link, rot_parent_to_child,
                           toBt(axis_in_child_com), parent_com_to_pivot, pivot_to_child_com,
                           /*disableParentCollision=*/true);
    } else {
      data.type = joint.type == urdf::Joint::CONTINUOUS ? JointType::continuous : JointType::revolute;
      body->setupRevolute(link, child.mass_kg, toBt(child.principal_moments), parent_link, rot_parent_to_child,
                          toBt(axis_in_child_com), parent_com_to_pivot, pivot_to_child_com,
                          /*disableParentCollision=*/true);
    }
    if (joint.limits && joint.limits->effort > 0.0) data.effort_limit = joint.limits->effort;
    data.motor_effort_limit = data.effort_limit;
    data.rotor_inertia = child.rotor_inertia.trace();  // k·a·aᵀ with |a| = 1 has trace k
    if (joint.dynamics) data.damping = joint.dynamics->damping;
    joints.push_back(std::move(data));
    joint_names.push_back(joint.name);
  }

  // Limits, command motors and friction motors: all created now so that
  // switching modes later only changes numbers.
  void createJointConstraints() {
    const double dt = settings.time_step_s;
    for (std::size_t j = 0; j < joints.size(); ++j) {
      const int link = static_cast<int>(j);
      JointData& data = joints[j];
      const urdf::Joint& joint = *tree.bodies[j + 1].joint;
      if (data.type != JointType::continuous && joint.limits && joint.limits->lower < joint.limits->upper) {
        auto limit = std::make_unique<btMultiBodyJointLimitConstraint>(body.get(), link, joint.limits->lower,
                                                                        joint.limits->upper);
        limit->setMaxAppliedImpulse(kRigidConstraintImpulse);
        world->addMultiBodyConstraint(limit.get());
        constraints.push_back(std::move(limit));
      }
      auto motor = std::make_unique<btMultiBodyJointMotor>(body.get(), link, 0.0, 0.0);
      motor->setErp(1.0);  // the position gain is set through kp alone
      data.command_motor = motor.get();
      world->addMultiBodyConstraint(motor.get());
      constraints.push_back(std::move(motor));
      if (joint.dynamics && joint.dynamics->friction > 0.0) {
        // Coulomb friction: a motor holding velocity 0 with at most `friction` effort.
        auto friction = std::make_unique<btMultiBodyJointMotor>(body.get(), link, 0.0, joint.dynamics->friction * dt);
        data.friction_motor = friction.get();
        world->addMultiBodyConstraint(friction.get());
        constraints.push_back(std::move(friction));
      }
    }
  }

  // <mimic joint multiplier offset>: q_m = multiplier·q_l + offset, held by a
  // gear constraint between the two links: its row is q̇_m + ratio·q̇_l = 0
  // with ratio = −multiplier, and its position target q_m + ratio·q_l = offset.
  void createMimicConstraints() {
    for (std::size_t j = 0; j < joints.size(); ++j) {
      const urdf::Joint& joint = *tree.bodies[j + 1].joint;
      if (!joint.mimic) continue;
      const auto leader = std::find(joint_names.begin(), joint_names.end(), joint.mimic->joint_name);
      if (leader == joint_names.end()) {
        throw ConfigError("joint '" + joint.name + "' <mimic joint=\"" + joint.mimic->joint_name +
                          "\">: no movable joint of that name; name a revolute, continuous or prismatic joint");
      }
      const int leader_link = static_cast<int>(leader - joint_names.begin());
      auto gear = std::make_unique<btMultiBodyGearConstraint>(body.get(), static_cast<int>(j), body.get(), leader_link,
                                                              btVector3(0, 0, 0), btVector3(0, 0, 0),
                                                              btMatrix3x3::getIdentity(), btMatrix3x3::getIdentity());
      gear->setGearRatio(-joint.mimic->multiplier);
      gear->setRelativePositionTarget(joint.mimic->offset);
      gear->setErp(kMimicErrorReduction);
      gear->setMaxAppliedImpulse(kRigidConstraintImpulse);
      world->addMultiBodyConstraint(gear.get());
      constraints.push_back(std::move(gear));
    }
  }

  // `body`: the body the shape belongs to (a wheel is a shape of the link its
  // joint turns, not one merged into it).
  btCollisionShape* makeShape(const detail::CollisionShapeSpec& spec, const detail::Body& body) {
    const urdf::Geometry& g = *spec.geometry;
    std::unique_ptr<btCollisionShape> shape;
    switch (g.type) {
      case urdf::Geometry::BOX: {
        const auto& box = static_cast<const urdf::Box&>(g);
        shape = std::make_unique<btBoxShape>(btVector3(box.dim.x, box.dim.y, box.dim.z) * 0.5);
        break;
      }
      case urdf::Geometry::CYLINDER: {
        const auto& cylinder = static_cast<const urdf::Cylinder&>(g);
        const bool wheel = spec.link_name == body.link_name &&
                           sim_common::isWheelCylinder(body.joint, spec.pose_in_body_link.linear(), cylinder.radius,
                                                       cylinder.length);
        shape = std::make_unique<btCylinderShapeZ>(
            btVector3(cylinder.radius, cylinder.radius, cylinder.length * 0.5));
        if (wheel) shape->setMargin(0.5 * cylinder.length);  // a tyre's profile (wheel_contact.hpp)
        break;
      }
      case urdf::Geometry::SPHERE:
        shape = std::make_unique<btSphereShape>(static_cast<const urdf::Sphere&>(g).radius);
        break;
      case urdf::Geometry::MESH: {
        const auto& mesh = static_cast<const urdf::Mesh&>(g);
        std::vector<Eigen::Vector3d> corners;
        try {
          corners = sim_common::collisionHullVertices(mesh.filename,
                                                      Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z));
        } catch (const ConfigError& error) {
          throw ConfigError("link '" + spec.link_name + "' <collision> mesh: " + error.what());
        }
        auto hull = std::make_unique<btConvexHullShape>();
        for (const auto& v : corners) hull->addPoint(toBt(v), /*recalculateLocalAabb=*/false);
        hull->recalcLocalAabb();
        hull->setMargin(kMeshCollisionMargin);
        shape = std::move(hull);
        break;
      }
      default:
        return nullptr;
    }
    shapes.push_back(std::move(shape));
    return shapes.back().get();
  }

  // Every body gets a collider, even without collision geometry: Bullet solves
  // a multibody's limits and motors only in the simulation island its link
  // colliders belong to, so a link without one would ignore its stops.
  void createColliders() {
    for (std::size_t k = 0; k < tree.bodies.size(); ++k) {
      const detail::Body& b = tree.bodies[k];
      auto compound = std::make_unique<btCompoundShape>();
      const Eigen::Isometry3d link_in_com = b.principal_in_link.inverse();
      auto friction = std::make_unique<std::vector<double>>();  // per compound child
      std::vector<std::string> child_links;
      for (const auto& spec : b.shapes) {
        if (btCollisionShape* shape = makeShape(spec, b)) {
          compound->addChildShape(toBt(link_in_com * spec.pose_in_body_link), shape);
          friction->push_back(sim_common::linkFriction(settings.link_friction, spec.link_name));
          child_links.push_back(spec.link_name);
        }
      }
      collider_child_links.push_back(std::move(child_links));
      const bool has_geometry = compound->getNumChildShapes() > 0;
      const int link = static_cast<int>(k) - 1;
      auto collider = std::make_unique<btMultiBodyLinkCollider>(body.get(), link);
      if (has_geometry) {
        collider->setCollisionShape(compound.get());
        shapes.push_back(std::move(compound));
      } else {
        auto empty = std::make_unique<btEmptyShape>();
        collider->setCollisionShape(empty.get());
        shapes.push_back(std::move(empty));
      }
      setFriction(*collider, std::move(friction));
      const bool is_static = link == -1 && fixed_base;
      // A collider without geometry is in no collision group and tests no group.
      int group = has_geometry ? int(btBroadphaseProxy::DefaultFilter) : 0;
      int mask = has_geometry ? int(btBroadphaseProxy::AllFilter) : 0;
      if (is_static) {
        collider->setCollisionFlags(collider->getCollisionFlags() | btCollisionObject::CF_STATIC_OBJECT);
      }
      if (is_static && has_geometry) {
        group = int(btBroadphaseProxy::StaticFilter);
        mask = int(btBroadphaseProxy::AllFilter) ^ int(btBroadphaseProxy::StaticFilter);
      }
      if (link == -1) {
        body->setBaseCollider(collider.get());
      } else {
        body->getLink(link).m_collider = collider.get();
      }
      world->addCollisionObject(collider.get(), group, mask);
      std::vector<std::string> collision_names;
      for (const std::string& child : collider_child_links.back()) {
        collision_names.push_back(robot_name + "::" + child + "::" + child + "_collision");
      }
      scene->collider_owners[collider.get()] = {robot_name, collider_child_links.back(), std::move(collision_names)};
      colliders.push_back(std::move(collider));
    }
  }

  // The URDF's friction (Gazebo's 1 when it sets none) instead of Bullet's
  // 0.5; one coefficient per merged link when they differ; combined with the
  // other surface's the scene's way (detail::useSceneFriction).
  void setFriction(btMultiBodyLinkCollider& collider, std::unique_ptr<std::vector<double>> per_child) {
    detail::useSceneFriction(collider);
    if (per_child->empty()) {
      collider.setFriction(sim_common::kDefaultContactFriction);
      return;
    }
    collider.setFriction(per_child->front());
    const bool uniform = std::all_of(per_child->begin(), per_child->end(),
                                     [&](double mu) { return mu == per_child->front(); });
    if (uniform) return;
    collider.setUserPointer(per_child.get());
    child_friction.push_back(std::move(per_child));
  }

  // --- state --------------------------------------------------------------

  // After a teleport: link transforms and collider poses follow at once.
  // After a teleport (and a reset): the sensors' next accelerations are unknown.
  void updateKinematics() {
    body->forwardKinematics(scratch_rotations, scratch_origins);
    body->updateCollisionObjectWorldTransforms(scratch_rotations, scratch_origins);
    sensors.forgetMotion();
  }

  double motorImpulse(const JointData& joint) const {
    const double effort =
        std::isfinite(joint.motor_effort_limit) ? joint.motor_effort_limit : kUnlimitedMotorEffort;
    return effort * settings.time_step_s;
  }

  void setMode(JointData& joint, CommandMode mode) {
    joint.mode = mode;
    joint.command_motor->setMaxAppliedImpulse(mode == CommandMode::effort ? 0.0 : motorImpulse(joint));
  }

  // Rotor inertias into the body tree, before the multibody is built from it.
  void addRotorInertias(const urdf::ModelInterface& model) {
    for (const auto& [joint_name, inertia] : settings.reflected_rotor_inertia) {
      const auto body = std::find_if(tree.bodies.begin() + 1, tree.bodies.end(),
                                     [&](const detail::Body& b) { return b.joint->name == joint_name; });
      const std::string where = "robot '" + model.getName() + "': rotor inertia for joint '" + joint_name + "'";
      if (body == tree.bodies.end()) {
        throw ConfigError(where + ": the robot has no revolute, continuous or prismatic joint of that name");
      }
      if (body->joint->type == urdf::Joint::PRISMATIC) {
        throw ConfigError(where + ": the Bullet world models rotor inertia on revolute and continuous joints "
                                  "only (a prismatic joint's reflected mass cannot be added to a link)");
      }
      if (!(inertia >= 0.0) || !std::isfinite(inertia)) {
        throw ConfigError(where + ": " + std::to_string(inertia) + " kg·m² must be a finite number >= 0");
      }
      if (inertia == 0.0) continue;
      const urdf::Vector3& axis = body->joint->axis;
      // The joint frame is the child link frame at q = 0, so the axis is in the body's link frame.
      detail::addRotorInertia(*body, Eigen::Vector3d(axis.x, axis.y, axis.z), inertia);
    }
  }

  Eigen::Isometry3d rootPose() const {
    return toEigen(body->getBaseWorldTransform()) * tree.bodies.front().principal_in_link.inverse();
  }
};

BulletWorld::BulletWorld(const urdf::ModelInterface& model, const WorldSettings& settings)
    : BulletWorld(model, settings, nullptr) {}

BulletWorld::BulletWorld(const urdf::ModelInterface& model, const WorldSettings& settings, BulletScene& scene)
    : BulletWorld(model, settings, &scene) {}

BulletWorld::BulletWorld(const urdf::ModelInterface& model, const WorldSettings& settings, BulletScene* scene)
    : impl_(std::make_unique<Impl>()) {
  if (!(settings.time_step_s > 0.0) || !std::isfinite(settings.time_step_s)) {
    throw ConfigError("Bullet world: time step " + std::to_string(settings.time_step_s) + " s must be > 0");
  }
  if (!(settings.position_motor_time_constant_s >= settings.time_step_s)) {
    throw ConfigError("Bullet world: position motor time constant " +
                      std::to_string(settings.position_motor_time_constant_s) + " s must be >= the time step");
  }
  if (!model.getRoot()) throw ConfigError("robot '" + model.getName() + "': no root link");
  std::size_t movable_joints = 0;
  for (const auto& [name, joint] : model.joints_) {
    if (joint && (joint->type == urdf::Joint::REVOLUTE || joint->type == urdf::Joint::CONTINUOUS ||
                  joint->type == urdf::Joint::PRISMATIC)) {
      ++movable_joints;
    }
  }
  if (movable_joints > kMaxMovableJoints) {
    throw ConfigError("robot '" + model.getName() + "' has " + std::to_string(movable_joints) +
                      " revolute, continuous and prismatic joints; the Bullet simulation takes at most " +
                      std::to_string(kMaxMovableJoints) +
                      " per robot (Bullet's multibody solver is dense: a step's memory and time grow with the "
                      "square of the joint count). Use the mock backend, or fewer movable joints (fixed joints "
                      "cost nothing)");
  }
  Impl& w = *impl_;
  w.settings = settings;
  w.tree = detail::buildBodyTree(model);
  for (std::size_t k = 1; k < w.tree.bodies.size(); ++k) {
    if (!(w.tree.bodies[k].mass_kg > 0.0)) {
      throw ConfigError("robot '" + model.getName() + "': link '" + w.tree.bodies[k].link_name +
                        "' has no mass; give it an <inertial> with <mass> > 0");
    }
  }
  w.decideBase(model);
  w.addRotorInertias(model);
  w.robot_name = model.getName();
  w.useScene(model, scene);
  w.createMultiBody();
  w.createJointConstraints();
  w.createMimicConstraints();
  w.createColliders();
  const int frames = static_cast<int>(w.tree.bodies.size());
  w.scratch_rotations.resize(frames);
  w.scratch_origins.resize(frames);
  w.resetMember();
  w.scene->reserveForMember(static_cast<int>(w.tree.bodies.size()), static_cast<int>(w.joints.size()));
  w.scene->members.push_back(&w);
  w.joined = true;
}

BulletWorld::~BulletWorld() = default;

std::size_t BulletWorld::numJoints() const { return impl_->joints.size(); }
const std::vector<std::string>& BulletWorld::jointNames() const { return impl_->joint_names; }

std::size_t BulletWorld::jointIndex(const std::string& name) const {
  const auto& names = impl_->joint_names;
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) {
    std::string known;
    for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
    throw Error("Bullet world: no movable joint '" + name + "' (movable joints: " + known + ")");
  }
  return static_cast<std::size_t>(it - names.begin());
}

JointType BulletWorld::jointType(std::size_t joint) const { return impl_->joints[joint].type; }
double BulletWorld::jointEffortLimit(std::size_t joint) const { return impl_->joints[joint].effort_limit; }
double BulletWorld::jointMotorEffortLimit(std::size_t joint) const { return impl_->joints[joint].motor_effort_limit; }
double BulletWorld::jointRotorInertia(std::size_t joint) const { return impl_->joints[joint].rotor_inertia; }
double BulletWorld::jointAppliedEffort(std::size_t joint) const { return impl_->joints[joint].applied_effort; }

void BulletWorld::setJointMotorEffortLimit(std::size_t joint, double limit) {
  assert(joint < impl_->joints.size());
  JointData& data = impl_->joints[joint];
  data.motor_effort_limit = limit >= 0.0 ? limit : 0.0;  // NaN or negative: the motor cannot push
  impl_->setMode(data, data.mode);                        // a running motor takes the new bound now
}

double BulletWorld::jointPosition(std::size_t joint) const { return impl_->body->getJointPos(int(joint)); }
double BulletWorld::jointVelocity(std::size_t joint) const { return impl_->body->getJointVel(int(joint)); }

void BulletWorld::setJointEffort(std::size_t joint, double effort) {
  assert(joint < impl_->joints.size());
  JointData& data = impl_->joints[joint];
  if (data.mode != CommandMode::effort) impl_->setMode(data, CommandMode::effort);
  data.pending_effort = effort;
}

void BulletWorld::setJointVelocityTarget(std::size_t joint, double velocity) {
  assert(joint < impl_->joints.size());
  JointData& data = impl_->joints[joint];
  impl_->setMode(data, CommandMode::velocity);
  data.pending_effort = 0.0;
  data.command_motor->setPositionTarget(0.0, /*kp=*/0.0);
  data.command_motor->setVelocityTarget(velocity, /*kd=*/1.0);
}

void BulletWorld::setJointPositionTarget(std::size_t joint, double position) {
  assert(joint < impl_->joints.size());
  JointData& data = impl_->joints[joint];
  impl_->setMode(data, CommandMode::position);
  data.pending_effort = 0.0;
  // Bullet's motor asks for the joint velocity kp*erp*(q_target - q)/dt + v + kd*(0 - v).
  // With erp = 1, kd = 1 and kp = dt/tau that is (q_target - q)/tau: a first-order
  // approach with time constant tau, bounded by the effort limit. (kp = 1 would
  // ask to close the error in one step, which under effort saturation overshoots
  // into an undamped bang-bang cycle.)
  const double kp = impl_->settings.time_step_s / impl_->settings.position_motor_time_constant_s;
  data.command_motor->setVelocityTarget(0.0, /*kd=*/1.0);
  data.command_motor->setPositionTarget(position, kp);
}

void BulletWorld::setJointState(std::size_t joint, double position, double velocity) {
  impl_->body->setJointPos(int(joint), position);
  impl_->body->setJointVel(int(joint), velocity);
  impl_->updateKinematics();
}

void BulletWorld::step() {
  if (impl_->own_scene) impl_->own_scene->step();
}

double BulletWorld::time() const { return static_cast<double>(impl_->steps) * impl_->settings.time_step_s; }
double BulletWorld::timeStep() const { return impl_->settings.time_step_s; }

void BulletWorld::reset() { impl_->resetMember(); }

bool BulletWorld::isFixedBase() const { return impl_->fixed_base; }

BaseState BulletWorld::baseState() const {
  const Impl& w = *impl_;
  const Eigen::Isometry3d root = w.rootPose();
  BaseState state;
  state.position = root.translation();
  state.orientation = Eigen::Quaterniond(root.linear());
  state.angular_velocity = toEigen(w.body->getBaseOmega());
  const Eigen::Vector3d com = toEigen(w.body->getBasePos());
  state.linear_velocity = toEigen(w.body->getBaseVel()) + state.angular_velocity.cross(state.position - com);
  return state;
}

void BulletWorld::setBaseState(const BaseState& state) {
  Impl& w = *impl_;
  if (w.fixed_base) return;
  Eigen::Isometry3d root = Eigen::Isometry3d::Identity();
  root.linear() = state.orientation.normalized().toRotationMatrix();
  root.translation() = state.position;
  const Eigen::Isometry3d com_pose = root * w.tree.bodies.front().principal_in_link;
  w.body->setBaseWorldTransform(toBt(com_pose));
  const Eigen::Vector3d com_velocity =
      state.linear_velocity + state.angular_velocity.cross(Eigen::Vector3d(com_pose.translation()) - state.position);
  w.body->setBaseVel(toBt(com_velocity));
  w.body->setBaseOmega(toBt(state.angular_velocity));
  w.updateKinematics();
}

Eigen::Vector3d BulletWorld::linkWorldPosition(const std::string& link_name) const {
  const Impl& w = *impl_;
  const auto it = w.tree.links.find(link_name);
  if (it == w.tree.links.end()) throw Error("Bullet world: no link '" + link_name + "' in the robot");
  const detail::Body& b = w.tree.bodies[it->second.body];
  const Eigen::Vector3d in_com = b.principal_in_link.inverse() * it->second.link_in_body_link.translation();
  return toEigen(w.body->localPosToWorld(it->second.body - 1, toBt(in_com)));
}

std::size_t BulletWorld::trackLink(const std::string& link_name) {
  impl_->sensors.reserve(*impl_->body);
  return impl_->sensors.trackLink(impl_->tree, link_name);
}

std::size_t BulletWorld::trackJointWrench(const std::string& joint_name) {
  return impl_->sensors.trackJointWrench(impl_->tree, *impl_->body, joint_name);
}

std::size_t BulletWorld::trackContacts(const std::string& link_name) {
  return impl_->sensors.trackContacts(impl_->tree, impl_->collider_child_links, link_name);
}

std::size_t BulletWorld::readContacts(std::size_t tracked, std::span<LinkContact> out) const {
  const Impl& w = *impl_;
  return w.sensors.readContacts(*w.body, *w.world->getDispatcher(), w.scene->collider_owners, w.scene->ground.get(),
                                w.settings.time_step_s, tracked, out);
}

LinkState BulletWorld::linkState(std::size_t tracked) const { return impl_->sensors.linkState(*impl_->body, tracked); }
JointWrench BulletWorld::jointWrench(std::size_t tracked) const { return impl_->sensors.jointWrench(tracked); }

BodyMassProperties BulletWorld::bodyMassProperties(const std::string& link_name) const {
  const Impl& w = *impl_;
  const auto it = w.tree.links.find(link_name);
  if (it == w.tree.links.end()) throw Error("Bullet world: no link '" + link_name + "' in the robot");
  const detail::Body& b = w.tree.bodies[it->second.body];
  return BodyMassProperties{b.mass_kg, b.com, b.inertia_about_com};
}

GroundPenetration BulletWorld::deepestGroundPenetration() const {
  const Impl& w = *impl_;
  GroundPenetration deepest;
  if (!w.scene->ground) return deepest;
  for (std::size_t k = 0; k < w.colliders.size(); ++k) {
    const btMultiBodyLinkCollider& collider = *w.colliders[k];
    if (collider.isStaticObject()) continue;
    const btCollisionShape* shape = collider.getCollisionShape();
    if (!shape->isCompound()) continue;  // a link without geometry
    const auto* compound = static_cast<const btCompoundShape*>(shape);
    for (int i = 0; i < compound->getNumChildShapes(); ++i) {
      if (!compound->getChildShape(i)->isConvex()) continue;
      const auto* convex = static_cast<const btConvexShape*>(compound->getChildShape(i));
      const btTransform child = collider.getWorldTransform() * compound->getChildTransform(i);
      // The shape's lowest point: its support point in the world's -z, with the margin.
      const btVector3 down_in_shape = child.getBasis().transpose() * btVector3(0, 0, -1);
      const double depth = -(child * convex->localGetSupportingVertex(down_in_shape)).z();
      if (depth > deepest.depth_m) deepest = {w.collider_child_links[k][static_cast<std::size_t>(i)], depth};
    }
  }
  return deepest;
}


MemberOverlap BulletWorld::deepestMemberOverlap() const {
  const Impl& w = *impl_;
  MemberOverlap deepest;
  w.world->updateAabbs();
  for (std::size_t k = 0; k < w.colliders.size(); ++k) {
    btMultiBodyLinkCollider& collider = *w.colliders[k];
    if (!collider.getCollisionShape()->isCompound()) continue;  // a link without geometry
    detail::OverlapProbe probe;
    probe.own = &w.colliders;
    probe.ground = w.scene->ground.get();
    w.world->contactTest(&collider, probe);
    if (probe.other != nullptr && probe.depth_m > deepest.depth_m) {
      deepest.depth_m = probe.depth_m;
      deepest.link = detail::childLink(w.collider_child_links[k], probe.own_child);
      const auto owner = w.scene->collider_owners.find(probe.other);
      deepest.other = owner == w.scene->collider_owners.end()
                          ? "another body"
                          : "robot '" + owner->second.robot + "' link '" +
                                detail::childLink(owner->second.child_links, probe.other_child) + "'";
    }
  }
  return deepest;
}

bool BulletWorld::usesDoublePrecision() { return std::is_same_v<btScalar, double> && sizeof(btScalar) == 8; }
double BulletWorld::linkLinearDamping() const { return impl_->body->getLinearDamping(); }
double BulletWorld::linkAngularDamping() const { return impl_->body->getAngularDamping(); }
double BulletWorld::maxCoordinateVelocity() const { return impl_->body->getMaxCoordinateVelocity(); }

}  // namespace servoloop::sim_bullet
