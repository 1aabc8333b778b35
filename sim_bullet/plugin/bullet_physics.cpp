#include "bullet_physics.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "servoloop/hardware_interface/errors.hpp"
#include "servoloop/hardware_interface/logging.hpp"

namespace servoloop::sim_bullet {

void BulletPhysics::init(const urdf::ModelInterface& model, const sim_common::SimSettings& settings,
                         const std::vector<sim_common::EngineJointConfig>& joints,
                         const std::string& source_name) {
  WorldSettings world_settings;
  world_settings.gravity = settings.gravity;
  world_settings.time_step_s = settings.time_step_s;
  world_settings.ground_plane = settings.ground_plane;
  world_ = std::make_unique<BulletWorld>(model, world_settings);

  world_index_.clear();
  initial_positions_.clear();
  for (const sim_common::EngineJointConfig& joint : joints) {
    try {
      world_index_.push_back(world_->jointIndex(joint.name));
    } catch (const Error& error) {
      throw ConfigError(source_name + ": " + error.what());
    }
    initial_positions_.push_back(joint.initial_position);

    const std::size_t index = world_index_.back();
    if (joint.reflected_rotor_inertia > 0.0) {
      logger().warn(
          "{}: joint '{}': the bullet backend does not model rotor inertia yet; the reflected "
          "{} kg·m² from <ns>/actuators/.../rotor_inertia is ignored",
          source_name, joint.name, joint.reflected_rotor_inertia);
    }
    if (joint.motor_effort_limit < world_->jointEffortLimit(index)) {
      logger().warn(
          "{}: joint '{}': velocity and position commands are bounded by the URDF effort limit "
          "({}), not by the tighter motor limit {} (effort commands honour it)",
          source_name, joint.name,
          std::isfinite(world_->jointEffortLimit(index)) ? std::to_string(world_->jointEffortLimit(index))
                                                          : std::string("none"),
          joint.motor_effort_limit);
    }
  }
  pending_efforts_.assign(joints.size(), 0.0);
  applied_efforts_.assign(joints.size(), 0.0);
  placeAtInitialPositions();
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

void BulletPhysics::setJointEffort(std::size_t joint, double effort) noexcept {
  const std::size_t index = world_index_[joint];
  const double limit = world_->jointEffortLimit(index);
  pending_efforts_[joint] = std::clamp(effort, -limit, limit);
  world_->setJointEffort(index, effort);
}

void BulletPhysics::setJointVelocityTarget(std::size_t joint, double velocity) noexcept {
  pending_efforts_[joint] = 0.0;
  world_->setJointVelocityTarget(world_index_[joint], velocity);
}

void BulletPhysics::setJointPositionTarget(std::size_t joint, double position) noexcept {
  pending_efforts_[joint] = 0.0;
  world_->setJointPositionTarget(world_index_[joint], position);
}

void BulletPhysics::step() noexcept {
  world_->step();
  // BulletWorld's effort acts for one step only.
  std::copy(pending_efforts_.begin(), pending_efforts_.end(), applied_efforts_.begin());
  std::fill(pending_efforts_.begin(), pending_efforts_.end(), 0.0);
}

void BulletPhysics::reset() {
  world_->reset();
  placeAtInitialPositions();
  std::fill(pending_efforts_.begin(), pending_efforts_.end(), 0.0);
  std::fill(applied_efforts_.begin(), applied_efforts_.end(), 0.0);
}

void BulletPhysics::setJointState(std::size_t joint, double position, double velocity) {
  world_->setJointState(world_index_.at(joint), position, velocity);
}

}  // namespace servoloop::sim_bullet
