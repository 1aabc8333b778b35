#include "body_sensors.hpp"

#include <algorithm>

#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include "servoloop/core/errors.hpp"

namespace servoloop::sim_bullet::detail {
namespace {
Eigen::Vector3d toEigen(const btVector3& v) { return Eigen::Vector3d(v.x(), v.y(), v.z()); }
Eigen::Matrix3d toEigen(const btMatrix3x3& m) {
  Eigen::Matrix3d out;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out(r, c) = m[r][c];
  }
  return out;
}
}  // namespace

std::size_t BodySensors::trackLink(const BodyTree& tree, const std::string& link_name) {
  const auto it = tree.links.find(link_name);
  if (it == tree.links.end()) throw ConfigError("Bullet world: no link '" + link_name + "' in the robot");
  const Body& body = tree.bodies[static_cast<std::size_t>(it->second.body)];
  links_.push_back(TrackedLink{it->second.body, body.principal_in_link.inverse() * it->second.link_in_body_link});
  motion_valid_ = false;
  return links_.size() - 1;
}

std::size_t BodySensors::trackJointWrench(const BodyTree& tree, const btMultiBody& body, const std::string& joint_name) {
  for (std::size_t b = 1; b < tree.bodies.size(); ++b) {
    const Body& child = tree.bodies[b];
    if (child.joint == nullptr || child.joint->name != joint_name) continue;
    for (std::size_t k = 0; k < joints_.size(); ++k) {
      if (joints_[k].body == static_cast<int>(b)) return k;
    }
    TrackedJoint tracked;
    tracked.body = static_cast<int>(b);
    tracked.link_in_frame = child.principal_in_link.inverse();
    // Bodies come depth-first, so the subtree is b and every later body whose
    // chain of parents reaches b.
    for (std::size_t k = b; k < tree.bodies.size(); ++k) {
      int up = static_cast<int>(k);
      while (up > static_cast<int>(b)) up = tree.bodies[static_cast<std::size_t>(up)].parent_body;
      if (up == static_cast<int>(b)) tracked.subtree.push_back(static_cast<int>(k));
    }
    joints_.push_back(std::move(tracked));
    reserve(body);
    return joints_.size() - 1;
  }
  throw ConfigError("joint '" + joint_name +
                    "' is not a movable joint: the bullet engine merges the links a fixed joint holds together into "
                    "one body, so it has no wrench to measure; put the force-torque sensor on a movable joint, or "
                    "simulate the robot with mujoco (which keeps fixed joints)");
}

std::size_t BodySensors::trackContacts(const BodyTree& tree,
                                       const std::vector<std::vector<std::string>>& collider_child_links,
                                       const std::string& link_name) {
  const auto it = tree.links.find(link_name);
  if (it == tree.links.end()) throw ConfigError("Bullet world: no link '" + link_name + "' in the robot");
  TrackedContacts tracked;
  tracked.body = it->second.body;
  const auto& children = collider_child_links.at(static_cast<std::size_t>(tracked.body));
  for (std::size_t c = 0; c < children.size(); ++c) {
    if (children[c] == link_name) tracked.children.push_back(static_cast<int>(c));
  }
  contacts_.push_back(std::move(tracked));
  return contacts_.size() - 1;
}

std::size_t BodySensors::readContacts(const btMultiBody& body, btDispatcher& dispatcher,
                                      const std::unordered_map<const btCollisionObject*, SceneCore::ColliderOwner>& owners,
                                      const btCollisionObject* ground, double dt, std::size_t tracked,
                                      std::span<LinkContact> out) const noexcept {
  static const std::string kGround = "ground_plane::link::collision";
  static const std::string kUnknown = "unknown::link::collision";
  const TrackedContacts& sensor = contacts_[tracked];
  const auto ours = [&](const btCollisionObject* object, int child) {
    const auto* collider = btMultiBodyLinkCollider::upcast(object);
    if (collider == nullptr || collider->m_multiBody != &body || collider->m_link + 1 != sensor.body) return false;
    for (const int c : sensor.children) {
      if (c == child) return true;
    }
    return false;
  };
  const auto name = [&](const btCollisionObject* object, int child) -> const std::string* {
    if (object == ground) return &kGround;
    const auto owner = owners.find(object);
    if (owner == owners.end()) return &kUnknown;
    const auto& names = owner->second.collision_names;
    if (child >= 0 && child < static_cast<int>(names.size())) return &names[static_cast<std::size_t>(child)];
    return names.size() == 1 ? &names.front() : &kUnknown;
  };
  std::size_t count = 0;
  const int manifolds = dispatcher.getNumManifolds();
  for (int m = 0; m < manifolds; ++m) {
    const btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(m);
    const btCollisionObject* a = manifold->getBody0();
    const btCollisionObject* b = manifold->getBody1();
    for (int p = 0; p < manifold->getNumContacts(); ++p) {
      const btManifoldPoint& point = manifold->getContactPoint(p);
      const bool on_a = ours(a, point.m_index0);
      const bool on_b = !on_a && ours(b, point.m_index1);
      if (!on_a && !on_b) continue;
      // Points Bullet keeps ahead of a touch (apart, no impulse) are not contacts yet.
      if (point.getDistance() > 0.0 && point.getAppliedImpulse() <= 0.0) continue;
      if (count < out.size()) {
        const double side = on_a ? 1.0 : -1.0;  // the normal impulse pushes A along the normal on B
        const btVector3 impulse = point.m_normalWorldOnB * point.getAppliedImpulse() +
                                  point.m_lateralFrictionDir1 * point.m_appliedImpulseLateral1 +
                                  point.m_lateralFrictionDir2 * point.m_appliedImpulseLateral2;
        LinkContact& contact = out[count];
        contact.other = on_a ? name(b, point.m_index1) : name(a, point.m_index0);
        contact.position = toEigen(on_a ? point.getPositionWorldOnA() : point.getPositionWorldOnB());
        contact.normal = side * toEigen(point.m_normalWorldOnB);
        contact.force = side * toEigen(impulse) / dt;
        contact.depth = std::max(0.0, -static_cast<double>(point.getDistance()));
      }
      ++count;
    }
  }
  return count;
}

void BodySensors::reserve(const btMultiBody& body) {
  const std::size_t bodies = static_cast<std::size_t>(body.getNumLinks()) + 1;
  omega_.assign(bodies, btVector3(0, 0, 0));
  velocity_.assign(bodies, btVector3(0, 0, 0));
  motion_.assign(bodies, BodyMotion{});
  last_motion_.assign(bodies, BodyMotion{});
  step_motion_.assign(bodies, BodyMotion{});
  angular_acceleration_.assign(bodies, Eigen::Vector3d::Zero());
  contact_force_.assign(bodies, Eigen::Vector3d::Zero());
  contact_moment_.assign(bodies, Eigen::Vector3d::Zero());
  has_last_motion_ = false;
}

void BodySensors::forgetMotion() noexcept {
  has_last_motion_ = false;
  motion_valid_ = false;
  for (TrackedJoint& joint : joints_) joint.wrench = JointWrench{};
}

void BodySensors::readMotion(const btMultiBody& body, std::vector<BodyMotion>& out) const noexcept {
  body.compTreeLinkVelocities(omega_.data(), velocity_.data());
  for (std::size_t k = 0; k < out.size(); ++k) {
    BodyMotion& motion = out[k];
    if (k == 0) {
      const btQuaternion& world_to_base = body.getWorldToBaseRot();
      motion.rotation =
          Eigen::Quaterniond(world_to_base.w(), world_to_base.x(), world_to_base.y(), world_to_base.z())
              .conjugate()
              .toRotationMatrix();
      motion.com = toEigen(body.getBasePos());
    } else {
      const int link = static_cast<int>(k) - 1;
      motion.rotation = toEigen(body.localFrameToWorld(link, btMatrix3x3::getIdentity()));
      motion.com = toEigen(body.localPosToWorld(link, btVector3(0, 0, 0)));
    }
    motion.velocity = toEigen(velocity_[k]);
    motion.omega = toEigen(omega_[k]);
  }
}

// The contact impulses of the step's manifolds, as forces on this robot's
// bodies: the normal impulse pushes body A along the normal on B, the
// friction impulses along their directions; body B gets the opposite.
void BodySensors::addContactForces(const btMultiBody& body, btDispatcher& dispatcher, double dt) noexcept {
  for (std::size_t k = 0; k < contact_force_.size(); ++k) {
    contact_force_[k].setZero();
    contact_moment_[k].setZero();
  }
  const int manifolds = dispatcher.getNumManifolds();
  for (int m = 0; m < manifolds; ++m) {
    const btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(m);
    const auto* a = btMultiBodyLinkCollider::upcast(manifold->getBody0());
    const auto* b = btMultiBodyLinkCollider::upcast(manifold->getBody1());
    const bool on_a = a != nullptr && a->m_multiBody == &body;
    const bool on_b = b != nullptr && b->m_multiBody == &body;
    if (!on_a && !on_b) continue;
    for (int p = 0; p < manifold->getNumContacts(); ++p) {
      const btManifoldPoint& point = manifold->getContactPoint(p);
      const btVector3 impulse = point.m_normalWorldOnB * point.getAppliedImpulse() +
                                point.m_lateralFrictionDir1 * point.m_appliedImpulseLateral1 +
                                point.m_lateralFrictionDir2 * point.m_appliedImpulseLateral2;
      const Eigen::Vector3d force = toEigen(impulse) / dt;
      if (on_a) {
        const std::size_t k = static_cast<std::size_t>(a->m_link + 1);
        contact_force_[k] += force;
        contact_moment_[k] += toEigen(point.getPositionWorldOnA()).cross(force);
      }
      if (on_b) {
        const std::size_t k = static_cast<std::size_t>(b->m_link + 1);
        contact_force_[k] -= force;
        contact_moment_[k] -= toEigen(point.getPositionWorldOnB()).cross(force);
      }
    }
  }
}

void BodySensors::afterStep(const btMultiBody& body, btDispatcher& dispatcher, double dt,
                            const btVector3& gravity_bt) noexcept {
  if (joints_.empty()) {
    motion_valid_ = false;  // link states alone: read when asked (linkState)
    return;
  }
  std::swap(motion_, last_motion_);
  readMotion(body, motion_);
  motion_valid_ = true;
  const bool accelerations_known = has_last_motion_;
  has_last_motion_ = true;
  addContactForces(body, dispatcher, dt);
  const Eigen::Vector3d gravity = toEigen(gravity_bt);

  // The step as Bullet's semi-implicit Euler takes it: the accelerations
  // the forces of the step's start state gave, so each body is taken where
  // the step started, with the change of its velocities over the step. The
  // change is taken in the body's own axes, a = R (dv/dt + ω × v), so that
  // a rotation alone does not show up as an acceleration.
  for (std::size_t k = 0; k < motion_.size(); ++k) {
    const BodyMotion& start = accelerations_known ? last_motion_[k] : motion_[k];
    const BodyMotion& end = motion_[k];
    BodyMotion& at = step_motion_[k];
    at.com = start.com;
    at.rotation = start.rotation;
    at.omega = start.rotation * start.omega;
    if (accelerations_known) {
      at.velocity = start.rotation * ((end.velocity - start.velocity) / dt + start.omega.cross(start.velocity));
      angular_acceleration_[k] = start.rotation * ((end.omega - start.omega) / dt);
    } else {
      at.velocity.setZero();
      angular_acceleration_[k].setZero();
    }
  }
  for (TrackedJoint& joint : joints_) {
    const BodyMotion& child = step_motion_[static_cast<std::size_t>(joint.body)];
    const Eigen::Vector3d pivot = child.com + child.rotation * joint.link_in_frame.translation();
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
    Eigen::Vector3d torque = Eigen::Vector3d::Zero();
    for (const int index : joint.subtree) {
      const std::size_t k = static_cast<std::size_t>(index);
      const BodyMotion& at = step_motion_[k];  // its velocity holds the acceleration
      const double mass = k == 0 ? body.getBaseMass() : body.getLinkMass(index - 1);
      const Eigen::Vector3d moments = toEigen(k == 0 ? body.getBaseInertia() : body.getLinkInertia(index - 1));
      const Eigen::Matrix3d inertia = at.rotation * moments.asDiagonal() * at.rotation.transpose();
      const Eigen::Vector3d inertial_force = mass * (at.velocity - gravity);
      force += inertial_force;
      torque += (at.com - pivot).cross(inertial_force) + inertia * angular_acceleration_[k] +
                at.omega.cross(inertia * at.omega);
      force -= contact_force_[k];
      torque -= contact_moment_[k] - pivot.cross(contact_force_[k]);
    }
    // Into the child link's axes.
    const Eigen::Matrix3d world_from_link = child.rotation * joint.link_in_frame.linear();
    joint.wrench.force = world_from_link.transpose() * force;
    joint.wrench.torque = world_from_link.transpose() * torque;
  }
}

LinkState BodySensors::linkState(const btMultiBody& body, std::size_t tracked) const noexcept {
  // Every body's motion is read once per step (afterStep), or here after a
  // teleport or reset; each tracked link is then one transform of it.
  if (!motion_valid_) {
    readMotion(body, motion_);
    motion_valid_ = true;
  }
  const TrackedLink& link = links_[tracked];
  const BodyMotion& frame = motion_[static_cast<std::size_t>(link.body)];
  const Eigen::Vector3d omega = frame.rotation * frame.omega;
  LinkState state;
  state.position = frame.com + frame.rotation * link.link_in_frame.translation();
  state.orientation = Eigen::Quaterniond(frame.rotation * link.link_in_frame.linear());
  state.angular_velocity = omega;
  state.linear_velocity = frame.rotation * frame.velocity + omega.cross(state.position - frame.com);
  return state;
}

JointWrench BodySensors::jointWrench(std::size_t tracked) const noexcept { return joints_[tracked].wrench; }

}  // namespace servoloop::sim_bullet::detail
