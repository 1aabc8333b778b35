#include "servoloop/node/model_states_publisher.hpp"

#include <algorithm>
#include <cmath>

#include "servoloop/core/errors.hpp"

namespace servoloop::node {

ModelStatesPublisher::ModelStatesPublisher(double time_step_s, double rate_hz) {
  if (!(time_step_s > 0.0) || !(rate_hz > 0.0) || !std::isfinite(time_step_s) || !std::isfinite(rate_hz)) {
    throw ConfigError("model states: the time step and the rate must be > 0");
  }
  // The nearest whole number of steps (50 Hz at 1 ms: every 20 steps).
  steps_per_message_ = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(1.0 / (rate_hz * time_step_s))));
}

void ModelStatesPublisher::setModels(std::vector<Model> models, realtime::TopicBus* bus) {
  models_ = std::move(models);
  gazebo_msgs::ModelStates prototype;
  for (const Model& model : models_) prototype.name.push_back(model.name);
  prototype.pose.assign(models_.size(), {});
  prototype.twist.assign(models_.size(), {});
  // A real-time publisher: the world's thread fills its staging message in
  // place, and nothing is copied while the topic has no subscriber.
  publisher_.reset();
  if (bus != nullptr && !models_.empty()) publisher_ = bus->advertise(kTopic, prototype);
}

std::uint64_t ModelStatesPublisher::betweenSegments(std::uint64_t steps) {
  if (steps < last_steps_) next_step_ = 0;  // the world was reset
  last_steps_ = steps;
  if (steps >= next_step_) {
    next_step_ = (steps / steps_per_message_ + 1) * steps_per_message_;
    if (publisher_.trylock()) {  // false also without a publisher (no bus or no models)
      gazebo_msgs::ModelStates& message = publisher_.msg();
      for (std::size_t i = 0; i < models_.size(); ++i) {
        const Model& model = models_[i];
        geometry_msgs::Pose& pose = message.pose[i];
        geometry_msgs::Twist& twist = message.twist[i];
        hardware_interface::BaseGroundTruth base;
        if (model.floating != nullptr && model.floating->readBaseGroundTruth(base)) {
          pose.position = {base.position[0], base.position[1], base.position[2]};
          pose.orientation = {base.orientation[0], base.orientation[1], base.orientation[2], base.orientation[3]};
          twist.linear = {base.linear_velocity[0], base.linear_velocity[1], base.linear_velocity[2]};
          twist.angular = {base.angular_velocity[0], base.angular_velocity[1], base.angular_velocity[2]};
        } else {
          pose = model.fixed_pose;
          twist = {};
        }
      }
      publisher_.unlockAndPublish();
    }
  }
  return next_step_ - steps;
}

}  // namespace servoloop::node
