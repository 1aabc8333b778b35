#pragma once
// The URDF tree reduced to the rigid bodies Bullet simulates: every link that
// a non-fixed joint moves (and the root) is one body; links attached by fixed
// joints are merged into it. Pure geometry and mass bookkeeping (Eigen only),
// so it can be checked without Bullet.
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <urdf_model/model.h>

namespace servoloop::sim_bullet::detail {

struct CollisionShapeSpec {
  const urdf::Geometry* geometry{nullptr};      // owned by the urdf model
  Eigen::Isometry3d pose_in_body_link{Eigen::Isometry3d::Identity()};
  std::string link_name;                         // the URDF link it came from, for messages
};

struct Body {
  std::string link_name;                // the link the body's joint moves (or the root link)
  int parent_body{-1};                  // index in BodyTree::bodies; -1 for the root
  const urdf::Joint* joint{nullptr};    // non-fixed joint to the parent body; null for the root
  // Joint frame (= child link frame at q = 0) in the parent body's link frame,
  // including any fixed joints between that link and the joint.
  Eigen::Isometry3d joint_in_parent_link{Eigen::Isometry3d::Identity()};

  // Merged mass properties from the URDF, in this body's link frame.
  double mass_kg{0.0};
  Eigen::Vector3d com{Eigen::Vector3d::Zero()};
  Eigen::Matrix3d inertia_about_com{Eigen::Matrix3d::Zero()};
  // Reflected rotor inertia of the body's joint, k·a·aᵀ (k = n²·J, a the unit
  // joint axis), in this body's link frame; zero unless addRotorInertia() was
  // called. Pure rotational inertia: no mass, so gravity and the centre of
  // mass are unchanged.
  Eigen::Matrix3d rotor_inertia{Eigen::Matrix3d::Zero()};
  // Principal frame of inertia_about_com + rotor_inertia: origin at the COM,
  // axes the eigenvectors (right-handed). Bullet's link frame is this frame.
  Eigen::Isometry3d principal_in_link{Eigen::Isometry3d::Identity()};
  Eigen::Vector3d principal_moments{Eigen::Vector3d::Zero()};

  std::vector<CollisionShapeSpec> shapes;
};

struct LinkPlacement {
  int body{0};
  Eigen::Isometry3d link_in_body_link{Eigen::Isometry3d::Identity()};
};

struct BodyTree {
  // Depth-first from the root; a parent always comes before its children, so
  // body k (k >= 1) is Bullet link k - 1 and joint index k - 1.
  std::vector<Body> bodies;
  std::map<std::string, LinkPlacement> links;  // every URDF link
};

// Throws ConfigError for joints the simulator cannot model (floating, planar).
BodyTree buildBodyTree(const urdf::ModelInterface& model);

Eigen::Isometry3d toIsometry(const urdf::Pose& pose);

// Adds `inertia` (kg·m², >= 0) about the unit axis `axis_in_link` (body link
// frame) to the body's rotational inertia and recomputes its principal frame.
// Must run before the Bullet multibody is built from the tree.
void addRotorInertia(Body& body, const Eigen::Vector3d& axis_in_link, double inertia);

}  // namespace servoloop::sim_bullet::detail
