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

std::size_t MujocoPhysics::trackContacts(const std::string& link) {
  constexpr std::size_t kMostContacts = 256;
  const int body = mj_name2id(m_, mjOBJ_BODY, (prefix_ + link).c_str());
  if (body < 0) throw ConfigError("MuJoCo model: no link '" + link + "' in the robot");
  ContactSensor sensor;
  sensor.link = link;
  sensor.body = body;
  sensor.contacts.resize(kMostContacts);
  contact_sensors_.push_back(std::move(sensor));
  bindSensors();
  return contact_sensors_.size() - 1;
}

void MujocoPhysics::bindSensors() {
  for (ContactSensor& sensor : contact_sensors_) {
    sensor.body = std::max(0, mj_name2id(m_, mjOBJ_BODY, (prefix_ + sensor.link).c_str()));
    sensor.count = 0;
  }
  body_collision_names_.clear();
  if (!contact_sensors_.empty()) {
    // Every body's collision as Gazebo scopes it; body 0 holds the ground.
    for (int b = 0; b < m_->nbody; ++b) {
      const char* name = mj_id2name(m_, mjOBJ_BODY, b);
      std::string link = name != nullptr ? name : "";
      std::string robot = robot_name_;
      const std::size_t slash = link.find('/');
      if (world_ != nullptr && slash != std::string::npos) {
        robot = world_->robotName(link.substr(0, slash + 1));
        link = link.substr(slash + 1);
      }
      body_collision_names_.push_back(b == 0 ? std::string("ground_plane::link::collision")
                                             : robot + "::" + link + "::" + link + "_collision");
    }
  }
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
void MujocoPhysics::captureSensorData() noexcept {
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
  captureContacts();
}

// A contact's force in its frame (normal, then the two tangents) turned
// into the world: the force geom1 applies to geom2, whose normal points from
// geom1 to geom2; the link on geom1's side gets the opposite.
void MujocoPhysics::captureContacts() noexcept {
  for (ContactSensor& sensor : contact_sensors_) sensor.count = 0;
  if (contact_sensors_.empty()) return;
  for (int i = 0; i < d_->ncon; ++i) {
    const mjContact& contact = d_->contact[i];
    if (contact.exclude != 0) continue;
    const int body1 = m_->geom_bodyid[contact.geom1];
    const int body2 = m_->geom_bodyid[contact.geom2];
    mjtNum local[6];
    mj_contactForce(m_, d_, i, local);
    const Eigen::Vector3d normal = vec3(contact.frame);
    const Eigen::Vector3d on_second =
        local[0] * normal + local[1] * vec3(contact.frame + 3) + local[2] * vec3(contact.frame + 6);
    for (ContactSensor& sensor : contact_sensors_) {
      if (sensor.body != body1 && sensor.body != body2) continue;
      const bool second = sensor.body == body2;
      if (sensor.count < sensor.contacts.size()) {
        sim_common::EngineContact& out = sensor.contacts[sensor.count];
        out.other = &body_collision_names_[static_cast<std::size_t>(second ? body1 : body2)];
        out.position = vec3(contact.pos);
        out.normal = second ? normal : Eigen::Vector3d(-normal);
        out.force = second ? on_second : Eigen::Vector3d(-on_second);
        out.depth = std::max(0.0, -contact.dist);
      }
      ++sensor.count;
    }
  }
}

std::size_t MujocoPhysics::readContacts(std::size_t tracked, std::span<sim_common::EngineContact> out) const noexcept {
  const ContactSensor& sensor = contact_sensors_[tracked];
  const std::size_t kept = std::min({sensor.count, sensor.contacts.size(), out.size()});
  for (std::size_t k = 0; k < kept; ++k) out[k] = sensor.contacts[k];
  return sensor.count;
}

void MujocoPhysics::readJointWrench(std::size_t tracked, sim_common::EngineJointWrench& out) const noexcept {
  out = joint_wrenches_[tracked];
}

}  // namespace servoloop::sim_mujoco
