#pragma once
// Topics between a node's topic bus and ROS 1, both ways, under the same
// names and types. Commands (the types a controller subscribes to:
// std_msgs/Float64, Float64MultiArray, Bool, geometry_msgs/Twist,
// trajectory_msgs/JointTrajectory) go from ROS to the node; states
// (sensor_msgs/JointState, control_msgs/*, nav_msgs/Odometry, tf2_msgs/TFMessage,
// diagnostic_msgs/DiagnosticArray, gazebo_msgs/ModelStates: the world's
// /gazebo/model_states, carried on the first robot's bus; the sensors'
// sensor_msgs/Imu, geometry_msgs/WrenchStamped and gazebo_msgs/ContactsState)
// go from the node to ROS. Topics are found with `topic.list` once a second,
// so controllers spawned later are bridged too, and a topic whose last
// publisher (to ROS) or subscriber (from ROS) in the node went away — its
// controller unloaded — is unadvertised (or unsubscribed) on the master, as
// ros_control's controllers do when they are unloaded; it is bridged again
// when it comes back. /clock follows the node's simulated time.
#include <atomic>
#include <map>
#include <set>
#include <string>

#include <nlohmann/json.hpp>
#include <ros/node_handle.h>
#include <ros/publisher.h>
#include <ros/subscriber.h>

#include "node_link.hpp"
#include "robot_state_cache.hpp"
#include "ros_message_json.hpp"

namespace servoloop::ros1 {

struct TopicBridgeOptions {
  double discovery_period_s = 1.0;
  // /clock is published when simulated time moves on, at most this often
  // (wall clock), and at least this often while the node runs.
  double clock_period_s = 0.005;
};

class TopicBridge {
 public:
  // `state` receives the robot's joint states, base ground truth and
  // simulated time as they pass.
  TopicBridge(ros::NodeHandle& nh, NodeLink& link, RobotStateCache& state, TopicBridgeOptions options = {});

  // Bridges until `stop` is set or ROS shuts down. Throws std::runtime_error
  // when the node's connection closes (the node ended).
  void run(const std::atomic<bool>& stop);

  // Topics bridged so far, for the log: name → "to ROS" / "from ROS".
  const std::map<std::string, std::string>& bridged() const { return directions_; }

 private:
  void discover();
  void bridgeTopic(const std::string& name, const std::string& type_name, const BridgedType& type);
  // Takes a bridged topic off the master (its ROS publisher or subscriber
  // and the node's stream of it dropped).
  void retire(const std::string& name);
  void forwardToRos(const nlohmann::json& stream_message);
  void publishClock(double sim_time);

  ros::NodeHandle& nh_;
  NodeLink& link_;
  RobotStateCache& state_;
  TopicBridgeOptions options_;
  NodeLink streams_;  // a link of its own: subscriptions, discovery, the clock
  std::string joint_states_topic_;  // what feeds `state_`
  std::string ground_truth_topic_;
  std::map<std::string, JsonPublisher> to_ros_;
  std::map<std::string, ros::Subscriber> from_ros_;
  std::map<std::string, std::string> directions_;
  // Bridged topics that have had a publisher (to ROS) or subscriber (from
  // ROS) of their own in the node: they are retired when it goes. Topics the
  // node publishes without advertising (/gazebo/model_states) never are.
  std::set<std::string> had_endpoint_;
  std::set<std::string> retired_;  // taken off; bridged again once an endpoint comes back
  std::set<std::string> skipped_;
  std::set<std::string> conversion_warned_;  // topics of types the bridge does not carry (reported once)
  ros::Publisher clock_;
  double last_clock_ = -1.0;
};

}  // namespace servoloop::ros1
