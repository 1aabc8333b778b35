#include "servoloop/node/world_snapshot.hpp"

#include <algorithm>
#include <cmath>

#include "servoloop/core/errors.hpp"

namespace servoloop::node {

WorldSnapshot::WorldSnapshot(double time_step_s, double rate_hz) : time_step_s_(time_step_s) {
  if (!(time_step_s > 0.0) || !(rate_hz > 0.0) || !std::isfinite(time_step_s) || !std::isfinite(rate_hz)) {
    throw ConfigError("world snapshot: the time step and the rate must be > 0");
  }
  steps_per_snapshot_ =
      std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(1.0 / (rate_hz * time_step_s))));
}

void WorldSnapshot::setModels(std::vector<Model> models, std::uint64_t steps) {
  models_ = std::move(models);
  {
    std::lock_guard lock(frame_mutex_);
    ++frame_.generation;
    frame_.models.resize(models_.size());
    for (std::size_t i = 0; i < models_.size(); ++i) {
      frame_.models[i].ns = models_[i].ns;
      frame_.models[i].joint_names = models_[i].joint_names;
      frame_.models[i].joint_positions.assign(models_[i].joint_positions.size(), 0.0);
    }
  }
  if (enabled()) take(steps);
}

std::uint64_t WorldSnapshot::betweenSegments(std::uint64_t steps) {
  if (steps < last_steps_) next_step_ = 0;  // the world was reset
  last_steps_ = steps;
  if (!enabled()) return steps_per_snapshot_;
  if (steps >= next_step_) {
    next_step_ = (steps / steps_per_snapshot_ + 1) * steps_per_snapshot_;
    take(steps);
  }
  return next_step_ - steps;
}

void WorldSnapshot::take(std::uint64_t steps) noexcept {
  std::unique_lock lock(frame_mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;  // a reader copies now: the next snapshot comes soon
  frame_.steps = steps;
  frame_.sim_time_s = static_cast<double>(steps) * time_step_s_;
  for (std::size_t i = 0; i < models_.size(); ++i) {
    const Model& model = models_[i];
    ModelFrame& out = frame_.models[i];
    hardware_interface::BaseGroundTruth base;
    if (model.floating != nullptr && model.floating->readBaseGroundTruth(base)) {
      std::copy(std::begin(base.position), std::end(base.position), out.pose);
      std::copy(std::begin(base.orientation), std::end(base.orientation), out.pose + 3);
    } else {
      std::copy(std::begin(model.fixed_pose), std::end(model.fixed_pose), out.pose);
    }
    for (std::size_t j = 0; j < model.joint_positions.size(); ++j) out.joint_positions[j] = *model.joint_positions[j];
  }
}

void WorldSnapshot::read(Frame& out) const {
  std::lock_guard lock(frame_mutex_);
  out = frame_;
}

}  // namespace servoloop::node
