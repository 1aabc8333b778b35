#include "raw_mujoco_pd.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "bench_support.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/sim_common/sim_settings.hpp"

namespace servoloop::bench {

RawMujocoPd::RawMujocoPd(const RobotCase& robot) : model_(loadRobotModelFile(sourcePath(robot.urdf))) {
  const YAML::Node params = robot.namespaceParams();
  std::vector<sim_common::EngineJointConfig> engine_joints;
  for (std::size_t i = 0; i < robot.joints.size(); ++i) {
    joints_.push_back(HandWrittenPositionLaw::forJoint(robot, params, i, *model_));
    sim_common::EngineJointConfig config;
    config.name = robot.joints[i];
    // Effort commands only: the motor bound is never used.
    config.motor_effort_limit = std::numeric_limits<double>::infinity();
    engine_joints.push_back(config);
  }
  sim_common::SimSettings settings;
  settings.time_step_s = kTimeStepS;
  physics_.init(*model_, settings, engine_joints, sourcePath(robot.urdf));
}

void RawMujocoPd::step() noexcept {
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    physics_.setJointEffort(j, joints_[j].effort(physics_.jointPosition(j), physics_.jointVelocity(j)));
  }
  physics_.step();
}

void RawMujocoPd::stepWithoutControl() noexcept {
  for (std::size_t j = 0; j < joints_.size(); ++j) physics_.setJointEffort(j, 0.0);
  physics_.step();
}

double RawMujocoPd::jointPosition(std::size_t controlled_joint) const {
  return physics_.jointPosition(controlled_joint);
}

double RawMujocoPd::maxAbsJointPosition() const {
  double largest = 0.0;
  for (std::size_t j = 0; j < joints_.size(); ++j) largest = std::max(largest, std::abs(physics_.jointPosition(j)));
  return largest;
}

}  // namespace servoloop::bench
