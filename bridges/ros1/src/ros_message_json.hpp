#pragma once
// The node's JSON message form (docs/node_operations.md, `topic.subscribe` and
// `topic.pub`) to and from ROS 1 messages, for the types the node's topic bus
// carries. The JSON form flattens a header into "stamp" (seconds of simulated
// time) and writes NaN as null; both directions keep those conventions, so a
// message crossing the bridge and back is unchanged.
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>
#include <ros/node_handle.h>
#include <ros/publisher.h>
#include <ros/subscriber.h>
#include <control_msgs/JointTrajectoryControllerState.h>
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>
#include <trajectory_msgs/JointTrajectory.h>
#include <trajectory_msgs/JointTrajectoryPoint.h>

namespace servoloop::ros1 {

// Publishes one node message (its JSON form) on a ROS topic.
using JsonPublisher = std::function<void(const nlohmann::json& msg)>;
// Receives one ROS message in the node's JSON form.
using JsonCallback = std::function<void(nlohmann::json msg)>;

struct BridgedType {
  std::string name;  // e.g. "sensor_msgs/JointState"
  // Commands go from ROS to the node (the node subscribes to them); states go
  // from the node to ROS.
  bool command = false;
  std::function<JsonPublisher(ros::NodeHandle& nh, const std::string& topic)> advertise;
  std::function<ros::Subscriber(ros::NodeHandle& nh, const std::string& topic, JsonCallback callback)> subscribe;
  // JSON → ROS message → serialised bytes → ROS message → JSON (for tests).
  std::function<nlohmann::json(const nlohmann::json& msg)> round_trip;
};

// Trajectories, a trajectory controller's state (a trajectory action's
// feedback), odometry (a floating base's ground truth) and a pose and twist
// (a model's state) in the node's JSON form, for the action bridge and the
// Gazebo services.
void fromJson(const nlohmann::json& j, trajectory_msgs::JointTrajectoryPoint& m);
nlohmann::json toJson(const trajectory_msgs::JointTrajectoryPoint& m);
void fromJson(const nlohmann::json& j, trajectory_msgs::JointTrajectory& m);
nlohmann::json toJson(const trajectory_msgs::JointTrajectory& m);
void fromJson(const nlohmann::json& j, control_msgs::JointTrajectoryControllerState& m);
nlohmann::json toJson(const control_msgs::JointTrajectoryControllerState& m);
void fromJson(const nlohmann::json& j, nav_msgs::Odometry& m);
nlohmann::json toJson(const nav_msgs::Odometry& m);
// {position: {x, y, z}, orientation: {x, y, z, w}}
void fromJson(const nlohmann::json& j, geometry_msgs::Pose& m);
nlohmann::json toJson(const geometry_msgs::Pose& m);
// {linear: {x, y, z}, angular: {x, y, z}}
void fromJson(const nlohmann::json& j, geometry_msgs::Twist& m);
nlohmann::json toJson(const geometry_msgs::Twist& m);

// The type, or nullptr when the bridge does not carry it.
const BridgedType* findBridgedType(std::string_view type_name);
std::vector<std::string> bridgedTypeNames();

// Exposed for tests: a message of `type_name` taken from JSON to its ROS form,
// serialised, read back and turned into JSON again.
nlohmann::json roundTrip(std::string_view type_name, const nlohmann::json& msg);

}  // namespace servoloop::ros1
