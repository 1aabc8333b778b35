#pragma once
// A PhysicsEngine that only records: the state is whatever the test sets, and
// every command the SimRobotHW hands over is kept, so the tests see exactly
// what would reach a physics engine.
#include <vector>

#include "servoloop/sim_common/physics_engine.hpp"

namespace servoloop::sim_testing {

class FakeEngine final : public sim_common::PhysicsEngine {
 public:
  struct Joint {
    double position = 0.0;
    double velocity = 0.0;
    double effort = 0.0;
    sim_common::JointCommandMode last_mode = sim_common::JointCommandMode::none;
    double last_command = 0.0;
    int commands_received = 0;
  };

  const char* name() const noexcept override { return "fake"; }

  void init(const urdf::ModelInterface& /*model*/, const sim_common::SimSettings& settings,
            const std::vector<sim_common::EngineJointConfig>& joints,
            const std::string& /*source_name*/) override {
    settings_seen = settings;
    configs = joints;
    state.assign(joints.size(), Joint{});
    reset();
  }

  double jointPosition(std::size_t j) const noexcept override { return state[j].position; }
  double jointVelocity(std::size_t j) const noexcept override { return state[j].velocity; }
  double jointEffort(std::size_t j) const noexcept override { return state[j].effort; }

  void setJointEffort(std::size_t j, double effort) noexcept override {
    record(j, sim_common::JointCommandMode::effort, effort);
  }
  void setJointVelocityTarget(std::size_t j, double velocity) noexcept override {
    record(j, sim_common::JointCommandMode::velocity, velocity);
  }
  void setJointPositionTarget(std::size_t j, double position) noexcept override {
    record(j, sim_common::JointCommandMode::position, position);
  }
  void step() noexcept override { ++steps; }

  void reset() override {
    ++resets;
    for (std::size_t j = 0; j < state.size(); ++j) {
      state[j] = Joint{};
      state[j].position = configs[j].initial_position;
    }
  }
  void setJointState(std::size_t j, double position, double velocity) override {
    state.at(j).position = position;
    state.at(j).velocity = velocity;
  }

  sim_common::SimSettings settings_seen;
  std::vector<sim_common::EngineJointConfig> configs;
  std::vector<Joint> state;
  int steps = 0;
  int resets = 0;

 private:
  void record(std::size_t j, sim_common::JointCommandMode mode, double value) noexcept {
    state[j].last_mode = mode;
    state[j].last_command = value;
    ++state[j].commands_received;
  }
};

}  // namespace servoloop::sim_testing
