#include "body_tree.hpp"

#include <vector>

#include <Eigen/Eigenvalues>

#include "servoloop/core/errors.hpp"

namespace servoloop::sim_bullet::detail {
namespace {

void updatePrincipalFrame(Body& body) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(body.inertia_about_com + body.rotor_inertia);
  Eigen::Matrix3d axes = solver.eigenvectors();
  if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);
  body.principal_in_link.linear() = axes;
  body.principal_in_link.translation() = body.com;
  body.principal_moments = solver.eigenvalues();
}

// One link's inertial expressed in its body's link frame.
struct PointMass {
  double mass{0.0};
  Eigen::Vector3d com{Eigen::Vector3d::Zero()};
  Eigen::Matrix3d inertia_about_com{Eigen::Matrix3d::Zero()};  // body link axes
};

class TreeBuilder {
 public:
  explicit TreeBuilder(const urdf::ModelInterface& model) : model_(model) {}

  BodyTree build() {
    const urdf::LinkConstSharedPtr root = model_.getRoot();
    if (!root) throw ConfigError("robot '" + model_.getName() + "': no root link");
    tree_.bodies.emplace_back();
    tree_.bodies.back().link_name = root->name;
    masses_.emplace_back();
    walk(*root);
    for (std::size_t k = 0; k < tree_.bodies.size(); ++k) finalizeMass(tree_.bodies[k], masses_[k]);
    return std::move(tree_);
  }

 private:
  // A link being walked: its body, its frame in that body's link frame, and
  // the next of its child joints to follow.
  struct Visit {
    const urdf::Link* link;
    int body;
    Eigen::Isometry3d link_in_body;
    std::size_t next_joint;
  };

  // Depth first from `root`, as a recursion over the links would go (each
  // link's shapes and mass first, then each child joint in order, a child's
  // whole subtree before the next child: bodies are numbered in that order),
  // but with the links being walked on an explicit stack: a recursion per
  // link would overflow the call stack on a chain of thousands of links.
  void walk(const urdf::Link& root) {
    std::vector<Visit> stack;
    enter(root, 0, Eigen::Isometry3d::Identity(), stack);
    while (!stack.empty()) {
      Visit& top = stack.back();
      if (top.next_joint == top.link->child_joints.size()) {
        stack.pop_back();
        continue;
      }
      const urdf::Link& link = *top.link;
      const int body = top.body;
      const Eigen::Isometry3d link_in_body = top.link_in_body;
      const urdf::JointSharedPtr& joint = link.child_joints[top.next_joint++];
      // (`top` is not used below: entering a child may move the stack.)
      urdf::LinkConstSharedPtr child = model_.getLink(joint->child_link_name);
      const Eigen::Isometry3d joint_in_body = link_in_body * toIsometry(joint->parent_to_joint_origin_transform);
      switch (joint->type) {
        case urdf::Joint::FIXED:
          enter(*child, body, joint_in_body, stack);
          break;
        case urdf::Joint::REVOLUTE:
        case urdf::Joint::CONTINUOUS:
        case urdf::Joint::PRISMATIC: {
          Body child_body;
          child_body.link_name = child->name;
          child_body.parent_body = body;
          child_body.joint = joint.get();
          child_body.joint_in_parent_link = joint_in_body;
          tree_.bodies.push_back(std::move(child_body));
          masses_.emplace_back();
          enter(*child, static_cast<int>(tree_.bodies.size()) - 1, Eigen::Isometry3d::Identity(), stack);
          break;
        }
        default:
          throw ConfigError("robot '" + model_.getName() + "': joint '" + joint->name +
                            "' is a floating or planar joint, which the Bullet simulation does not support; "
                            "use revolute, continuous, prismatic or fixed joints");
      }
    }
  }

  // Places `link` in `body` and adds its mass and shapes to the body; its
  // child joints are followed from the stack.
  void enter(const urdf::Link& link, int body, const Eigen::Isometry3d& link_in_body, std::vector<Visit>& stack) {
    tree_.links[link.name] = LinkPlacement{body, link_in_body};
    if (link.inertial) {
      const Eigen::Isometry3d inertial_in_body = link_in_body * toIsometry(link.inertial->origin);
      const urdf::Inertial& in = *link.inertial;
      Eigen::Matrix3d local;
      local << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
      const Eigen::Matrix3d r = inertial_in_body.linear();
      masses_[body].push_back(PointMass{in.mass, inertial_in_body.translation(), r * local * r.transpose()});
    }
    for (const auto& collision : link.collision_array) {
      if (!collision || !collision->geometry) continue;
      tree_.bodies[body].shapes.push_back(
          CollisionShapeSpec{collision->geometry.get(), link_in_body * toIsometry(collision->origin), link.name});
    }
    stack.push_back(Visit{&link, body, link_in_body, 0});
  }

  // Combined mass, centre of mass and inertia (parallel-axis theorem), then
  // the principal frame Bullet needs (it takes a diagonal inertia).
  static void finalizeMass(Body& body, const std::vector<PointMass>& parts) {
    double mass = 0.0;
    Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
    for (const auto& p : parts) {
      mass += p.mass;
      first_moment += p.mass * p.com;
    }
    body.mass_kg = mass;
    if (mass <= 0.0) return;  // a massless body: only valid as a fixed base (checked by the world)
    body.com = first_moment / mass;
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
    for (const auto& p : parts) {
      const Eigen::Vector3d d = p.com - body.com;
      inertia += p.inertia_about_com + p.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
    }
    body.inertia_about_com = inertia;
    updatePrincipalFrame(body);
  }

  const urdf::ModelInterface& model_;
  BodyTree tree_;
  std::vector<std::vector<PointMass>> masses_;  // per body
};

}  // namespace

Eigen::Isometry3d toIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  t.linear() = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
                   .normalized()
                   .toRotationMatrix();
  return t;
}

BodyTree buildBodyTree(const urdf::ModelInterface& model) { return TreeBuilder(model).build(); }

void addRotorInertia(Body& body, const Eigen::Vector3d& axis_in_link, double inertia) {
  const Eigen::Vector3d axis = axis_in_link.normalized();
  body.rotor_inertia += inertia * axis * axis.transpose();
  updatePrincipalFrame(body);
}

}  // namespace servoloop::sim_bullet::detail
