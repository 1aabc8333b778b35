#pragma once
// What a robot's sensors read from its btMultiBody: the state of any URDF
// link frame (also one merged into a body by fixed joints) and the wrench a
// movable joint transmits. Kept apart from the world's construction;
// BulletWorld forwards to it.
//
// The wrench is what the parent must supply for the motion the step gave
// the joint's subtree (Newton-Euler over the step, at the step's start
// state, whose forces Bullet's semi-implicit Euler applies): with each
// body's acceleration a and angular acceleration α from the change of its
// velocities over the step, gravity g and the contact forces F_c on the
// subtree,
//   F = Σ m (a - g) - Σ F_c
//   τ_p = Σ [(c - p) × m (a - g) + I α + ω × I ω] - Σ (r_c - p) × F_c
// about the joint origin p. Bullet's own joint feedback is not used: its
// second (constraint) pass counts joint torques and velocity terms twice.
#include <cstddef>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "body_tree.hpp"
#include "bullet_scene_core.hpp"
#include "servoloop/sim_bullet/bullet_world.hpp"

namespace servoloop::sim_bullet::detail {

class BodySensors {
 public:
  // Non-real-time. Throws servoloop::ConfigError naming an unknown link.
  std::size_t trackLink(const BodyTree& tree, const std::string& link_name);
  // Non-real-time. Measures the joint that moves a body of the tree.
  // Throws servoloop::ConfigError for a fixed joint (its links are merged
  // into one body, so nothing is transmitted to measure) or a name that is
  // no joint of the tree.
  std::size_t trackJointWrench(const BodyTree& tree, const btMultiBody& body, const std::string& joint_name);
  // Non-real-time: sizes the velocity scratch for `body` (call after the
  // multibody is built and before linkState).
  void reserve(const btMultiBody& body);

  // Non-real-time. Contacts of the compound children that came from
  // `link_name` (collider_child_links: per body, each child's URDF link).
  // Throws servoloop::ConfigError for an unknown link.
  std::size_t trackContacts(const BodyTree& tree, const std::vector<std::vector<std::string>>& collider_child_links,
                            const std::string& link_name);
  // Real-time. The tracked link's contact points in the dispatcher's
  // manifolds (the last step's), named through `owners` (the ground:
  // "ground_plane::link::collision"); dt turns impulses into forces.
  std::size_t readContacts(const btMultiBody& body, btDispatcher& dispatcher,
                           const std::unordered_map<const btCollisionObject*, SceneCore::ColliderOwner>& owners,
                           const btCollisionObject* ground, double dt, std::size_t tracked,
                           std::span<LinkContact> out) const noexcept;

  // Real-time, after every step of the scene (dt s, gravity m/s²): the
  // tracked joints' wrenches of that step. Without tracked joints, only
  // marks the link states as stale (linkState reads them when asked).
  void afterStep(const btMultiBody& body, btDispatcher& dispatcher, double dt, const btVector3& gravity) noexcept;
  // Every measured wrench back to zero and the last velocities forgotten
  // (a reset or a teleport: the next step's accelerations are not known).
  void forgetMotion() noexcept;

  // Real-time.
  LinkState linkState(const btMultiBody& body, std::size_t tracked) const noexcept;
  JointWrench jointWrench(std::size_t tracked) const noexcept;

 private:
  struct TrackedLink {
    int body = 0;  // BodyTree index: Bullet link body - 1, or the base for 0
    // The URDF link frame in Bullet's frame of the body (its principal
    // frame at the centre of mass).
    Eigen::Isometry3d link_in_frame{Eigen::Isometry3d::Identity()};
  };
  struct TrackedJoint {
    int body = 0;                // BodyTree index of the child body
    std::vector<int> subtree;    // it and every body below it
    // The child link frame (the joint frame) in Bullet's frame of the child body.
    Eigen::Isometry3d link_in_frame{Eigen::Isometry3d::Identity()};
    JointWrench wrench;  // of the last step, child link axes
  };
  // One body's motion, Bullet's frame at its centre of mass: its pose in
  // the world, its velocities in its own axes.
  struct BodyMotion {
    Eigen::Matrix3d rotation{Eigen::Matrix3d::Identity()};
    Eigen::Vector3d com{Eigen::Vector3d::Zero()};
    Eigen::Vector3d velocity{Eigen::Vector3d::Zero()};
    Eigen::Vector3d omega{Eigen::Vector3d::Zero()};
  };

  void readMotion(const btMultiBody& body, std::vector<BodyMotion>& out) const noexcept;
  void addContactForces(const btMultiBody& body, btDispatcher& dispatcher, double dt) noexcept;

  struct TrackedContacts {
    int body = 0;               // BodyTree index
    std::vector<int> children;  // the link's children in the body's compound shape
  };

  std::vector<TrackedLink> links_;
  std::vector<TrackedContacts> contacts_;
  std::vector<TrackedJoint> joints_;
  // compTreeLinkVelocities' output, one entry per body.
  mutable std::vector<btVector3> omega_;
  mutable std::vector<btVector3> velocity_;
  // Per body: its motion now (valid after a step; read again when not) and
  // at the last step, for the link states and the wrenches, and the contact
  // force on it and its moment about the world origin.
  mutable std::vector<BodyMotion> motion_;
  mutable bool motion_valid_ = false;
  std::vector<BodyMotion> last_motion_;
  // Each body at the step's start, world axes; velocity holds its acceleration.
  std::vector<BodyMotion> step_motion_;
  std::vector<Eigen::Vector3d> angular_acceleration_;
  bool has_last_motion_ = false;
  std::vector<Eigen::Vector3d> contact_force_;
  std::vector<Eigen::Vector3d> contact_moment_;
};

}  // namespace servoloop::sim_bullet::detail
