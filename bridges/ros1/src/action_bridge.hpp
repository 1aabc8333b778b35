#pragma once
// The node's actions as actionlib action servers under the same names
// (<ns>/<controller>/follow_joint_trajectory, .../gripper_cmd), so ROS action
// clients (actionlib's SimpleActionClient, MoveIt, rostopic on the goal and
// result topics) drive servoloop's trajectory and gripper controllers.
//
// A goal from ROS is sent to the node (action.send) and accepted, or rejected
// when the node rejects it; its state, feedback and result are read from the
// node (action.status) on every poll() and passed on: SUCCEEDED, ABORTED
// (with the controller's error code), PREEMPTED and CANCELED (both canceled,
// as ros_control's controllers end a preempted goal). A cancel from ROS is sent
// to the node. Goals are tracked on the bridge's own connection.
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>

#include <nlohmann/json.hpp>
#include <ros/node_handle.h>

#include "node_link.hpp"

namespace servoloop::ros1 {

// One action server; implemented per action type in action_bridge.cpp.
class BridgedAction {
 public:
  virtual ~BridgedAction() = default;
  // Reads the node's state of every goal in flight and passes it to ROS.
  virtual void poll() = 0;
};

class ActionBridge {
 public:
  // `link` is the actions' own connection (the node answers action.status
  // only on the connection that sent the goal).
  ActionBridge(ros::NodeHandle& nh, NodeLink& link);

  // Serves the node's actions not served yet (action.list).
  void discover();
  void poll();

  std::size_t served() const { return actions_.size(); }

 private:
  ros::NodeHandle& nh_;
  NodeLink& link_;
  std::map<std::string, std::unique_ptr<BridgedAction>> actions_;
  std::set<std::string> skipped_;
};

}  // namespace servoloop::ros1
