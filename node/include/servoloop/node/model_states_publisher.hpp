#pragma once
// Every model's pose and twist on /gazebo/model_states
// (gazebo_msgs/ModelStates), as Gazebo publishes them: the world frame, a
// floating base's ground truth and a fixed base's spawn pose (at rest), at a
// fixed rate of world time. Published by the world's thread between two
// segments of cycles (world/world_loop.hpp's WorldObserver), so never inside
// a control cycle.
#include <cstdint>
#include <string>
#include <vector>

#include "servoloop/hardware_interface/simulated_robot_hw.hpp"
#include "servoloop/realtime/messages.hpp"
#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/world/world_loop.hpp"

namespace servoloop::node {

class ModelStatesPublisher final : public world::WorldObserver {
 public:
  static constexpr double kDefaultRateHz = 50.0;
  static constexpr const char* kTopic = "/gazebo/model_states";

  struct Model {
    std::string name;
    // A floating base, read at each message; nullptr for a fixed one.
    const hardware_interface::SimulatedRobotHW* floating = nullptr;
    geometry_msgs::Pose fixed_pose;
  };

  // `time_step_s`: the world's physics step. Throws servoloop::ConfigError
  // for a rate or step that is not > 0.
  explicit ModelStatesPublisher(double time_step_s, double rate_hz = kDefaultRateHz);

  // Non-real-time, with the world standing (WorldLoop::whilePaused) or not
  // yet started: the models to publish and the bus carrying the topic
  // (nullptr: publish nothing). The models' hardware must stay valid until
  // replaced; the bus must outlive this publisher.
  void setModels(std::vector<Model> models, realtime::TopicBus* bus);

  // World thread, between segments: publishes when a message is due.
  std::uint64_t betweenSegments(std::uint64_t steps) override;

  // Steps between two messages.
  std::uint64_t stepsPerMessage() const noexcept { return steps_per_message_; }

 private:
  std::uint64_t steps_per_message_ = 1;
  std::uint64_t next_step_ = 0;
  std::uint64_t last_steps_ = 0;
  std::vector<Model> models_;
  realtime::RealtimePublisher<gazebo_msgs::ModelStates> publisher_;
};

}  // namespace servoloop::node
