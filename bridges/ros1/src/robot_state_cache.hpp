#pragma once
// The newest joint states and base ground truth the bridge has seen from the
// node, and the node's simulated time, for the Gazebo services (read on ROS's
// callback threads, written by the stream thread).
#include <atomic>
#include <map>
#include <mutex>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace servoloop::ros1 {

struct JointSample {
  double position = 0.0;
  double velocity = 0.0;
};

class RobotStateCache {
 public:
  // A sensor_msgs/JointState in the node's JSON form.
  void updateJoints(const nlohmann::json& joint_state);
  // A nav_msgs/Odometry in the node's JSON form (<ns>/ground_truth/odom).
  void updateGroundTruth(const nlohmann::json& odometry);
  void updateSimTime(double sim_time) { sim_time_.store(sim_time); }

  std::optional<JointSample> joint(const std::string& name) const;
  std::optional<nlohmann::json> groundTruth() const;
  double simTime() const { return sim_time_.load(); }
  // True once a joint state arrived.
  bool hasJoints() const;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, JointSample> joints_;
  std::optional<nlohmann::json> ground_truth_;
  std::atomic<double> sim_time_{0.0};
};

}  // namespace servoloop::ros1
