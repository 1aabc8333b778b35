#include "action_bridge.hpp"

#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include <actionlib/server/action_server.h>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <control_msgs/GripperCommandAction.h>
#include <ros/ros.h>

#include "ros_message_json.hpp"

namespace servoloop::ros1 {
namespace {

using nlohmann::json;

double numberOrNan(const json& parent, const char* key) {
  const auto it = parent.find(key);
  if (it == parent.end() || !it->is_number()) return std::nan("");
  return it->get<double>();
}

// --- per action type: goal to JSON, feedback and result from JSON ----------------
json tolerancesToJson(const std::vector<control_msgs::JointTolerance>& tolerances) {
  json out = json::array();
  for (const auto& t : tolerances) {
    out.push_back({{"name", t.name}, {"position", t.position}, {"velocity", t.velocity}, {"acceleration", t.acceleration}});
  }
  return out;
}

json goalToJson(const control_msgs::FollowJointTrajectoryGoal& goal) {
  json trajectory = toJson(goal.trajectory);
  return {{"trajectory", std::move(trajectory)},
          {"path_tolerance", tolerancesToJson(goal.path_tolerance)},
          {"goal_tolerance", tolerancesToJson(goal.goal_tolerance)},
          {"goal_time_tolerance", goal.goal_time_tolerance.toSec()}};
}

// The node writes a trajectory goal's feedback as the controller's state.
void feedbackFromJson(const json& j, control_msgs::FollowJointTrajectoryFeedback& out) {
  control_msgs::JointTrajectoryControllerState state;
  fromJson(j, state);
  out.header = state.header;
  out.joint_names = std::move(state.joint_names);
  out.desired = std::move(state.desired);
  out.actual = std::move(state.actual);
  out.error = std::move(state.error);
}

void resultFromJson(const json& j, control_msgs::FollowJointTrajectoryResult& out) {
  out.error_code = j.value("error_code", 0);
  out.error_string = j.value("error_string", "");
}

json goalToJson(const control_msgs::GripperCommandGoal& goal) {
  return {{"command", {{"position", goal.command.position}, {"max_effort", goal.command.max_effort}}}};
}

template <class Out>
void gripperStateFromJson(const json& j, Out& out) {
  out.position = numberOrNan(j, "position");
  out.effort = numberOrNan(j, "effort");
  out.stalled = j.value("stalled", false);
  out.reached_goal = j.value("reached_goal", false);
}
void feedbackFromJson(const json& j, control_msgs::GripperCommandFeedback& out) { gripperStateFromJson(j, out); }
void resultFromJson(const json& j, control_msgs::GripperCommandResult& out) { gripperStateFromJson(j, out); }

// --- the server ---------------------------------------------------------------------
template <class Action>
class ActionServerBridge final : public BridgedAction {
 public:
  ACTION_DEFINITION(Action);
  using Server = actionlib::ActionServer<Action>;
  using GoalHandle = typename Server::GoalHandle;

  ActionServerBridge(ros::NodeHandle& nh, NodeLink& link, std::string name, std::string type)
      : link_(link), name_(std::move(name)), type_(std::move(type)),
        server_(nh, name_, [this](GoalHandle goal) { onGoal(std::move(goal)); },
                [this](GoalHandle goal) { onCancel(std::move(goal)); }, false) {
    server_.start();
  }

  void poll() override {
    std::vector<std::pair<std::int64_t, GoalHandle>> in_flight;
    {
      std::lock_guard lock(mutex_);
      in_flight.assign(goals_.begin(), goals_.end());
    }
    for (auto& [goal_id, handle] : in_flight) {
      // A cancel that came while the goal was being sent found no goal id
      // yet: actionlib left the goal PREEMPTING; pass the cancel on now.
      if (handle.getGoalStatus().status == actionlib_msgs::GoalStatus::PREEMPTING && cancel_sent_.insert(goal_id).second) {
        try {
          link_.call("action.cancel", {{"goal_id", goal_id}});
        } catch (const std::exception& e) {
          ROS_WARN("%s: cancel not delivered: %s", name_.c_str(), e.what());
        }
      }
      json status;
      try {
        status = link_.call("action.status", {{"goal_id", goal_id}});
      } catch (const std::exception& e) {
        // The node forgot the goal (it ended, or the connection was replaced).
        Result result;
        handle.setAborted(result, std::string("servoloop: ") + e.what());
        forget(goal_id);
        continue;
      }
      const std::string state = status.value("state", "");
      if (const auto feedback = status.find("feedback"); feedback != status.end() && feedback->is_object()) {
        Feedback ros_feedback;
        feedbackFromJson(*feedback, ros_feedback);
        handle.publishFeedback(ros_feedback);
      }
      if (state == "PENDING" || state == "ACTIVE") continue;
      Result result;
      if (const auto node_result = status.find("result"); node_result != status.end() && node_result->is_object()) {
        resultFromJson(*node_result, result);
      }
      if (state == "SUCCEEDED") {
        handle.setSucceeded(result);
      } else if (state == "ABORTED" || state == "REJECTED") {
        handle.setAborted(result);
      } else {
        handle.setCanceled(result);  // PREEMPTED, CANCELED
      }
      forget(goal_id);
    }
  }

 private:
  void onGoal(GoalHandle handle) {
    json reply;
    try {
      reply = link_.call("action.send", {{"name", name_}, {"type", type_}, {"goal", goalToJson(*handle.getGoal())}});
    } catch (const std::exception& e) {
      ROS_ERROR("%s: goal rejected: %s", name_.c_str(), e.what());
      handle.setRejected(Result(), e.what());
      return;
    }
    if (reply.value("state", "") == "REJECTED") {
      handle.setRejected(Result(), "rejected by the controller");
      try {
        // Reading the ended goal's status lets the node forget it.
        link_.call("action.status", {{"goal_id", reply.at("goal_id")}});
      } catch (const std::exception&) {
      }
      return;
    }
    handle.setAccepted();
    std::lock_guard lock(mutex_);
    goals_.emplace(reply.at("goal_id").get<std::int64_t>(), std::move(handle));
  }

  void onCancel(GoalHandle handle) {
    std::int64_t goal_id = -1;
    {
      std::lock_guard lock(mutex_);
      for (const auto& [id, tracked] : goals_) {
        if (tracked == handle) goal_id = id;
      }
    }
    if (goal_id < 0) return;
    try {
      link_.call("action.cancel", {{"goal_id", goal_id}});  // poll() passes the CANCELED state on
    } catch (const std::exception& e) {
      ROS_WARN("%s: cancel not delivered: %s", name_.c_str(), e.what());
    }
  }

  void forget(std::int64_t goal_id) {
    cancel_sent_.erase(goal_id);
    std::lock_guard lock(mutex_);
    goals_.erase(goal_id);
  }

  NodeLink& link_;
  std::string name_;
  std::string type_;
  std::mutex mutex_;
  std::map<std::int64_t, GoalHandle> goals_;
  std::set<std::int64_t> cancel_sent_;  // poll()'s own
  Server server_;  // last: its callbacks use the members above
};

}  // namespace

ActionBridge::ActionBridge(ros::NodeHandle& nh, NodeLink& link) : nh_(nh), link_(link) {}

void ActionBridge::discover() {
  const json reply = link_.call("action.list");
  for (const json& action : reply.value("actions", json::array())) {
    const std::string name = action.value("name", "");
    const std::string type = action.value("type", "");
    if (name.empty() || actions_.count(name) != 0 || skipped_.count(name) != 0) continue;
    try {
      if (type == "control_msgs/FollowJointTrajectory") {
        actions_.emplace(name, std::make_unique<ActionServerBridge<control_msgs::FollowJointTrajectoryAction>>(nh_, link_, name, type));
      } else if (type == "control_msgs/GripperCommand") {
        actions_.emplace(name, std::make_unique<ActionServerBridge<control_msgs::GripperCommandAction>>(nh_, link_, name, type));
      }
    } catch (const ros::InvalidNameException& e) {
      ROS_WARN("servoloop bridge: action %s stays in servoloop: ROS does not accept its name (%s)", name.c_str(), e.what());
      skipped_.insert(name);
      continue;
    }
    if (type != "control_msgs/FollowJointTrajectory" && type != "control_msgs/GripperCommand") {
      ROS_WARN("servoloop bridge: action %s has type %s, which the bridge does not serve", name.c_str(), type.c_str());
      skipped_.insert(name);
      continue;
    }
    ROS_INFO("servoloop bridge: action %s (%s) served", name.c_str(), type.c_str());
  }
}

void ActionBridge::poll() {
  for (auto& [name, action] : actions_) action->poll();
}

}  // namespace servoloop::ros1
