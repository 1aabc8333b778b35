#pragma once
// The command side of a PhysicsEngine whose step() acts on each joint's latest
// command (mock, mujoco): the setters and applyJointCommands() only store the
// command, so every such engine shares them here and keeps only its step().
// An engine that hands commands on to a world object at once (bullet)
// implements the setters itself.
#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

#include "servoloop/sim_common/physics_engine.hpp"

namespace servoloop::sim_common {

// Threading as PhysicsEngine: resizeJointCommands() is non-real-time; the
// setters, applyJointCommands() and the protected accessors run on the
// real-time thread (they only read and write the table sized at init).
class StoredCommandPhysicsEngine : public PhysicsEngine {
 public:
  // Real-time. Store the command for the next step(), in joint space.
  void setJointEffort(std::size_t joint, double effort) noexcept final {
    commands_[joint] = {JointCommandMode::effort, effort};
  }
  void setJointVelocityTarget(std::size_t joint, double velocity) noexcept final {
    commands_[joint] = {JointCommandMode::velocity, velocity};
  }
  void setJointPositionTarget(std::size_t joint, double position) noexcept final {
    commands_[joint] = {JointCommandMode::position, position};
  }
  // Real-time. One copy of the whole table instead of a setter call per
  // joint. Mode none is stored as it comes: step() treats it as an effort,
  // which is what the setters would have made of it.
  void applyJointCommands(std::span<const AppliedJointCommand> commands) noexcept final {
    std::copy_n(commands.begin(), std::min(commands.size(), commands_.size()), commands_.begin());
  }

 protected:
  // Non-real-time (init). One command per joint, all cleared.
  void resizeJointCommands(std::size_t joint_count) { commands_.assign(joint_count, AppliedJointCommand{}); }
  // Every joint back to mode none with a zero value (reset).
  void clearJointCommands() noexcept { std::fill(commands_.begin(), commands_.end(), AppliedJointCommand{}); }

  // Real-time. The command step() acts on: an effort for modes none and
  // effort, else the motor's velocity or position target.
  const AppliedJointCommand& jointCommand(std::size_t joint) const noexcept { return commands_[joint]; }
  // Real-time. An effort acts for one step only: step() calls this once the
  // step has used the efforts. Motor targets stay in force.
  void endEffortCommands() noexcept {
    for (AppliedJointCommand& command : commands_) {
      if (command.mode == JointCommandMode::none || command.mode == JointCommandMode::effort) command.value = 0.0;
    }
  }

 private:
  std::vector<AppliedJointCommand> commands_;  // per joint, init()'s joint order
};

}  // namespace servoloop::sim_common
