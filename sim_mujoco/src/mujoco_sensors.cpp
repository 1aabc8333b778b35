// MujocoPhysics' sensors: link frames from the bodies (each body frame is its
// URDF link's frame), joint wrenches from the interaction forces of the
// step's forward pass.
#include <algorithm>

#include <Eigen/Geometry>

#include <mujoco/mujoco.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/sim_mujoco/mujoco_physics.hpp"

namespace servoloop::sim_mujoco {
namespace {
Eigen::Vector3d vec3(const mjtNum* v) { return Eigen::Vector3d(v[0], v[1], v[2]); }
}  // namespace

std::size_t MujocoPhysics::trackLink(const std::string& link) {
  const int body = link == "world" ? 0 : mj_name2id(m_, mjOBJ_BODY, (prefix_ + link).c_str());
  if (body < 0) throw ConfigError("MuJoCo model: no link '" + link + "' in the robot");
  tracked_link_names_.push_back(link);
  tracked_link_bodies_.push_back(body);
  return tracked_link_names_.size() - 1;
}

std::size_t MujocoPhysics::trackJointWrench(const std::string& joint) {
  const auto it = joint_child_links_.find(joint);
  const int body = it == joint_child_links_.end() ? -1 : mj_name2id(m_, mjOBJ_BODY, (prefix_ + it->second).c_str());
  if (body <= 0) throw ConfigError("MuJoCo model: no joint '" + joint + "' in the robot");
  tracked_joint_links_.push_back(it->second);
  tracked_joint_bodies_.push_back(body);
  joint_wrenches_.emplace_back();
  return tracked_joint_links_.size() - 1;
}

void MujocoPhysics::bindSensors() {
  for (std::size_t k = 0; k < tracked_link_names_.size(); ++k) {
    const std::string& link = tracked_link_names_[k];
    tracked_link_bodies_[k] = link == "world" ? 0 : std::max(0, mj_name2id(m_, mjOBJ_BODY, (prefix_ + link).c_str()));
  }
  for (std::size_t k = 0; k < tracked_joint_links_.size(); ++k) {
    tracked_joint_bodies_[k] = std::max(0, mj_name2id(m_, mjOBJ_BODY, (prefix_ + tracked_joint_links_[k]).c_str()));
  }
}

void MujocoPhysics::readLinkState(std::size_t tracked, sim_common::EngineLinkState& out) const noexcept {
  const int body = tracked_link_bodies_[tracked];
  const mjtNum* q = d_->xquat + 4 * body;
  out.position = vec3(d_->xpos + 3 * body);
  out.orientation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
  mjtNum velocity[6];  // angular, then linear, of the body frame's origin (XBODY, not the inertial frame), world axes
  mj_objectVelocity(m_, d_, mjOBJ_XBODY, body, velocity, 0);
  out.angular_velocity = vec3(velocity);
  out.linear_velocity = vec3(velocity + 3);
}

// cfrc_int: the force the parent applies to the body (and what hangs from
// it), as torque then force, about the centre of mass of the body's whole
// tree (subtree_com of its root), world axes. Moved to the joint origin (the
// body frame's origin) and turned into the body's axes.
void MujocoPhysics::captureJointWrenches() noexcept {
  for (std::size_t k = 0; k < tracked_joint_bodies_.size(); ++k) {
    const int body = tracked_joint_bodies_[k];
    const mjtNum* interaction = d_->cfrc_int + 6 * body;
    const Eigen::Vector3d force = vec3(interaction + 3);
    const Eigen::Vector3d reference = vec3(d_->subtree_com + 3 * m_->body_rootid[body]);
    const Eigen::Vector3d origin = vec3(d_->xpos + 3 * body);
    const Eigen::Vector3d torque = vec3(interaction) + (reference - origin).cross(force);
    const Eigen::Map<const Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor>> world_from_body(d_->xmat + 9 * body);
    joint_wrenches_[k].force = world_from_body.transpose() * force;
    joint_wrenches_[k].torque = world_from_body.transpose() * torque;
  }
}

void MujocoPhysics::readJointWrench(std::size_t tracked, sim_common::EngineJointWrench& out) const noexcept {
  out = joint_wrenches_[tracked];
}

}  // namespace servoloop::sim_mujoco
