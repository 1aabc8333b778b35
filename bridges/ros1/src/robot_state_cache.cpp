#include "robot_state_cache.hpp"

#include <cmath>
#include <limits>

namespace servoloop::ros1 {

namespace {
double at(const nlohmann::json& list, std::size_t i) {
  if (!list.is_array() || i >= list.size() || !list[i].is_number()) return std::numeric_limits<double>::quiet_NaN();
  return list[i].get<double>();
}
}  // namespace

void RobotStateCache::updateJoints(const nlohmann::json& joint_state) {
  const nlohmann::json names = joint_state.value("name", nlohmann::json::array());
  const nlohmann::json positions = joint_state.value("position", nlohmann::json::array());
  const nlohmann::json velocities = joint_state.value("velocity", nlohmann::json::array());
  std::lock_guard lock(mutex_);
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (!names[i].is_string()) continue;
    joints_[names[i].get<std::string>()] = JointSample{at(positions, i), at(velocities, i)};
  }
}

void RobotStateCache::updateGroundTruth(const nlohmann::json& odometry) {
  std::lock_guard lock(mutex_);
  ground_truth_ = odometry;
}

std::optional<JointSample> RobotStateCache::joint(const std::string& name) const {
  std::lock_guard lock(mutex_);
  const auto it = joints_.find(name);
  if (it == joints_.end()) return std::nullopt;
  return it->second;
}

std::optional<nlohmann::json> RobotStateCache::groundTruth() const {
  std::lock_guard lock(mutex_);
  return ground_truth_;
}

bool RobotStateCache::hasJoints() const {
  std::lock_guard lock(mutex_);
  return !joints_.empty();
}

}  // namespace servoloop::ros1
