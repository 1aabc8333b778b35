#include "bullet_physics.hpp"

#include "bullet_simulated_world.hpp"
#include <algorithm>
#include <string>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/sim_common/ground_penetration.hpp"

namespace servoloop::sim_bullet {
namespace {

// True when a movable joint lies between `joint`'s parent link and the root:
// then the rotor inertia added to `joint`'s child body is also felt by that
// joint (unless the axes are perpendicular).
bool hasMovableAncestor(const urdf::ModelInterface& model, const urdf::Joint& joint) {
  urdf::LinkConstSharedPtr link = model.getLink(joint.parent_link_name);
  while (link && link->parent_joint) {
    if (link->parent_joint->type != urdf::Joint::FIXED) return true;
    link = model.getLink(link->parent_joint->parent_link_name);
  }
  return false;
}

}  // namespace

void BulletPhysics::joinWorld(hardware_interface::SimulatedWorld& world) {
  auto* bullet_world = dynamic_cast<BulletSimulatedWorld*>(&world);
  if (bullet_world == nullptr) {
    sim_common::PhysicsEngine::joinWorld(world);  // robots apart: a scene of its own
    return;
  }
  if (bullet_world->scene() == nullptr) throw Error("bullet: a robot joined a world that was not initialised");
  shared_scene_ = bullet_world->scene();
}

void BulletPhysics::init(const urdf::ModelInterface& model, const sim_common::SimSettings& settings,
                         const std::vector<sim_common::EngineJointConfig>& joints,
                         const std::string& source_name) {
  WorldSettings world_settings;
  world_settings.gravity = settings.gravity;
  world_settings.time_step_s = settings.time_step_s;
  world_settings.ground_plane = settings.ground_plane;
  world_settings.fixed_base = sim_common::isFixedBase(model, settings.base) ? FixedBase::fixed : FixedBase::floating;
  world_settings.initial_base_position = settings.base_position;
  world_settings.initial_base_orientation = settings.base_orientation;
  world_settings.self_collision = settings.self_collide;
  world_settings.link_friction = settings.link_friction;
  for (const sim_common::EngineJointConfig& joint : joints) {
    if (!(joint.reflected_rotor_inertia > 0.0)) continue;
    const urdf::JointConstSharedPtr urdf_joint = model.getJoint(joint.name);
    if (urdf_joint && urdf_joint->type == urdf::Joint::PRISMATIC) {
      logger().warn(
          "{}: joint '{}': the bullet backend does not model rotor inertia on prismatic joints; the reflected "
          "{} kg from <ns>/actuators/.../rotor_inertia is ignored",
          source_name, joint.name, joint.reflected_rotor_inertia);
      continue;
    }
    world_settings.reflected_rotor_inertia[joint.name] = joint.reflected_rotor_inertia;
    if (urdf_joint && hasMovableAncestor(model, *urdf_joint)) {
      logger().info(
          "{}: joint '{}': the bullet backend adds its reflected rotor inertia ({} kg·m²) to the child link "
          "about the joint axis; the joints above it feel part of it too (see docs/simulation.md)",
          source_name, joint.name, joint.reflected_rotor_inertia);
    }
  }
  try {
    world_ = shared_scene_ != nullptr ? std::make_unique<BulletWorld>(model, world_settings, *shared_scene_)
                                      : std::make_unique<BulletWorld>(model, world_settings);
  } catch (const ConfigError& error) {
    throw ConfigError(source_name + ": " + error.what());
  }

  world_index_.clear();
  initial_positions_.clear();
  motor_effort_limits_.clear();
  for (const sim_common::EngineJointConfig& joint : joints) {
    try {
      world_index_.push_back(world_->jointIndex(joint.name));
    } catch (const Error& error) {
      throw ConfigError(source_name + ": " + error.what());
    }
    initial_positions_.push_back(joint.initial_position);
    motor_effort_limits_.push_back(sim_common::motorEffortBound(joint));
  }
  applyMotorEffortLimits();
  placeAtInitialPositions();
  const GroundPenetration deepest = world_->deepestGroundPenetration();
  sim_common::warnIfStartsBelowGround(model, settings, source_name, deepest.link, deepest.depth_m);
  if (shared_scene_ != nullptr) {
    const MemberOverlap overlap = world_->deepestMemberOverlap();
    if (overlap.depth_m > sim_common::kGroundPenetrationWarningDepth_m) {
      logger().warn(
          "{}: link '{}' starts {:.3f} m inside {} at its spawn pose; the contact pushes the two apart with a jolt "
          "at the first step. Spawn it elsewhere (launch file: pose: [x, y, z]; spawn-model: -x -y -z)",
          source_name, overlap.link, overlap.depth_m, overlap.other);
    }
  }
}

bool BulletPhysics::readBaseState(sim_common::EngineBaseState& out) const noexcept {
  if (!world_ || world_->isFixedBase()) return false;
  const BaseState base = world_->baseState();
  out.position = base.position;
  out.orientation = base.orientation;
  out.linear_velocity = base.linear_velocity;
  out.angular_velocity = base.angular_velocity;
  return true;
}

void BulletPhysics::setBaseState(const sim_common::EngineBaseState& state) {
  if (!world_ || world_->isFixedBase()) sim_common::PhysicsEngine::setBaseState(state);
  BaseState base;
  base.position = state.position;
  base.orientation = state.orientation;
  base.linear_velocity = state.linear_velocity;
  base.angular_velocity = state.angular_velocity;
  world_->setBaseState(base);
}

void BulletPhysics::applyMotorEffortLimits() {
  for (std::size_t j = 0; j < world_index_.size(); ++j) {
    world_->setJointMotorEffortLimit(world_index_[j], motor_effort_limits_[j]);
  }
}

void BulletPhysics::placeAtInitialPositions() {
  for (std::size_t j = 0; j < world_index_.size(); ++j) {
    world_->setJointState(world_index_[j], initial_positions_[j], 0.0);
  }
}

double BulletPhysics::jointPosition(std::size_t joint) const noexcept {
  return world_->jointPosition(world_index_[joint]);
}

double BulletPhysics::jointVelocity(std::size_t joint) const noexcept {
  return world_->jointVelocity(world_index_[joint]);
}

double BulletPhysics::jointEffort(std::size_t joint) const noexcept {
  return world_->jointAppliedEffort(world_index_[joint]);
}

void BulletPhysics::setJointEffort(std::size_t joint, double effort) noexcept {
  world_->setJointEffort(world_index_[joint], effort);
}

void BulletPhysics::setJointVelocityTarget(std::size_t joint, double velocity) noexcept {
  world_->setJointVelocityTarget(world_index_[joint], velocity);
}

void BulletPhysics::setJointPositionTarget(std::size_t joint, double position) noexcept {
  world_->setJointPositionTarget(world_index_[joint], position);
}

// BulletPhysics is final: the per-joint calls in these loops bind statically.
void BulletPhysics::readJointStates(std::span<sim_common::EngineJointState> states) const noexcept {
  sim_common::readJointStatesVia(*this, states);
}

void BulletPhysics::applyJointCommands(std::span<const sim_common::AppliedJointCommand> commands) noexcept {
  sim_common::applyJointCommandsVia(*this, commands);
}

void BulletPhysics::step() noexcept { world_->step(); }

std::size_t BulletPhysics::trackLink(const std::string& link) { return world_->trackLink(link); }

void BulletPhysics::readLinkState(std::size_t tracked, sim_common::EngineLinkState& out) const noexcept {
  const LinkState state = world_->linkState(tracked);
  out.position = state.position;
  out.orientation = state.orientation;
  out.linear_velocity = state.linear_velocity;
  out.angular_velocity = state.angular_velocity;
}

std::size_t BulletPhysics::trackContacts(const std::string& link) {
  constexpr std::size_t kMostContacts = 256;
  contacts_.resize(kMostContacts);
  return world_->trackContacts(link);
}

std::size_t BulletPhysics::readContacts(std::size_t tracked, std::span<sim_common::EngineContact> out) const noexcept {
  const std::size_t count = world_->readContacts(tracked, std::span<LinkContact>(contacts_.data(), std::min(out.size(), contacts_.size())));
  for (std::size_t k = 0; k < std::min(count, out.size()); ++k) {
    const LinkContact& contact = contacts_[k];
    out[k] = sim_common::EngineContact{contact.other, contact.position, contact.normal, contact.force, contact.depth};
  }
  return count;
}

std::size_t BulletPhysics::trackJointWrench(const std::string& joint) { return world_->trackJointWrench(joint); }

void BulletPhysics::readJointWrench(std::size_t tracked, sim_common::EngineJointWrench& out) const noexcept {
  const JointWrench wrench = world_->jointWrench(tracked);
  out.force = wrench.force;
  out.torque = wrench.torque;
}

void BulletPhysics::reset() {
  world_->reset();
  placeAtInitialPositions();
}

void BulletPhysics::setJointState(std::size_t joint, double position, double velocity) {
  world_->setJointState(world_index_.at(joint), position, velocity);
}

}  // namespace servoloop::sim_bullet
