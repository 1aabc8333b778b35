#include "servoloop/sim_common/joint_axis_inertia.hpp"

#include <algorithm>
#include <vector>

#include <Eigen/Geometry>

#include "servoloop/core/errors.hpp"

namespace servoloop::sim_common {
namespace {

Eigen::Isometry3d toIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.linear() =
      Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
          .normalized()
          .toRotationMatrix();
  transform.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return transform;
}

struct AxisInertia {
  double mass_kg = 0.0;
  double rotational_kg_m2 = 0.0;
};

// Adds `link`'s mass properties; `link_in_joint`: the link frame in the
// joint frame (the child link's frame is the joint frame at position 0).
void addLink(const urdf::Link& link, const Eigen::Isometry3d& link_in_joint, const Eigen::Vector3d& axis,
             AxisInertia& total) {
  if (!link.inertial) return;
  const urdf::Inertial& inertial = *link.inertial;
  const Eigen::Isometry3d com_frame = link_in_joint * toIsometry(inertial.origin);
  Eigen::Matrix3d inertia_com;
  inertia_com << inertial.ixx, inertial.ixy, inertial.ixz,  //
      inertial.ixy, inertial.iyy, inertial.iyz,             //
      inertial.ixz, inertial.iyz, inertial.izz;
  const Eigen::Matrix3d rotation = com_frame.linear();
  const Eigen::Vector3d com = com_frame.translation();
  const Eigen::Vector3d com_off_axis = com - axis * axis.dot(com);
  total.mass_kg += inertial.mass;
  total.rotational_kg_m2 += axis.dot(rotation * inertia_com * rotation.transpose() * axis) +
                            inertial.mass * com_off_axis.squaredNorm();
}

// Adds `subtree_root` and its descendants, depth first with the children in
// the order of the link's child joints (the sums' order), from an explicit
// stack: a recursion per link would overflow the call stack on a chain of
// thousands of links.
void accumulate(const urdf::Link& subtree_root, const Eigen::Vector3d& axis, AxisInertia& total) {
  struct Pending {
    const urdf::Link* link;
    Eigen::Isometry3d link_in_joint;
  };
  std::vector<Pending> stack{Pending{&subtree_root, Eigen::Isometry3d::Identity()}};
  while (!stack.empty()) {
    const Pending pending = stack.back();
    stack.pop_back();
    const urdf::Link& link = *pending.link;
    addLink(link, pending.link_in_joint, axis, total);
    // The last child joint goes on first, so that the first comes off next.
    for (auto joint = link.child_joints.rbegin(); joint != link.child_joints.rend(); ++joint) {
      const auto& child_joint = *joint;
      const auto child = std::find_if(link.child_links.begin(), link.child_links.end(),
                                      [&](const auto& l) { return l->name == child_joint->child_link_name; });
      if (child == link.child_links.end()) continue;
      stack.push_back(
          Pending{child->get(), pending.link_in_joint * toIsometry(child_joint->parent_to_joint_origin_transform)});
    }
  }
}

}  // namespace

double jointAxisInertia(const urdf::ModelInterface& model, const std::string& joint_name) {
  const auto joint_it = model.joints_.find(joint_name);
  if (joint_it == model.joints_.end() || !joint_it->second) {
    throw ConfigError("robot '" + model.getName() + "': no joint '" + joint_name + "'");
  }
  const urdf::Joint& joint = *joint_it->second;
  const bool rotational = joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::CONTINUOUS;
  if (!rotational && joint.type != urdf::Joint::PRISMATIC) {
    throw ConfigError("robot '" + model.getName() + "': joint '" + joint_name +
                      "' is not revolute, continuous or prismatic");
  }
  const auto link_it = model.links_.find(joint.child_link_name);
  if (link_it == model.links_.end() || !link_it->second) {
    throw ConfigError("robot '" + model.getName() + "': joint '" + joint_name + "' has no child link '" +
                      joint.child_link_name + "'");
  }
  Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
  if (axis.norm() == 0.0) axis = Eigen::Vector3d::UnitX();  // URDF's default axis
  axis.normalize();

  AxisInertia total;
  accumulate(*link_it->second, axis, total);
  const double inertia = rotational ? total.rotational_kg_m2 : total.mass_kg;
  if (!(inertia > 0.0)) {
    throw ConfigError("robot '" + model.getName() + "': joint '" + joint_name + "' moves no " +
                      (rotational ? "inertia about its axis" : "mass") +
                      "; give link '" + joint.child_link_name + "' an <inertial>");
  }
  return inertia;
}

}  // namespace servoloop::sim_common
