#pragma once
// Gazebo's joint and model services, as a ROS node written against Gazebo
// calls them (the seed tutorial's minimal_joint_controller does):
//
//   /gazebo/get_joint_properties  a joint's type and damping (the URDF's) and
//                                 its position and rate (the newest joint
//                                 state the node published);
//   /gazebo/apply_joint_effort    an effort on a joint from start_time for
//                                 duration (negative: until the bridge ends);
//                                 efforts applied at once add up, as in
//                                 Gazebo. servoloop applies them through the
//                                 running effort_controllers/JointEffortController
//                                 that claims the joint: the bridge publishes
//                                 the sum on its command topic whenever it
//                                 changes (in the node's simulated time, read
//                                 every 1 ms of wall time);
//   /gazebo/pause_physics, /gazebo/unpause_physics, /gazebo/reset_simulation,
//   /gazebo/reset_world           the world's controls (servoloop world ...;
//                                 both resets also restart the time);
//   /gazebo/set_model_configuration  joint positions of a model, at rest.
//
// The model services (get_model_state, set_model_state, spawn_urdf_model,
// delete_model) are in gazebo_model_services.hpp.
//
// A call the bridge cannot serve answers success=false with the reason in
// status_message (for example, no effort controller on the joint).
#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <ros/node_handle.h>
#include <ros/service_server.h>

#include "node_link.hpp"
#include "robot_state_cache.hpp"

namespace servoloop::ros1 {

// One joint of the robot description, as Gazebo reports it.
struct UrdfJoint {
  int gazebo_type = 0;  // gazebo_msgs/GetJointProperties REVOLUTE, CONTINUOUS, ...
  double damping = 0.0;
};

// The joints of a URDF (name → type and damping); throws std::runtime_error
// when the XML does not read.
std::map<std::string, UrdfJoint> urdfJoints(const std::string& urdf_xml);

// Efforts applied over windows of simulated time; the sum at a time.
class EffortSchedule {
 public:
  // From max(start_s, now_s); duration_s < 0: without end; 0: nothing.
  void apply(double effort, double start_s, double duration_s, double now_s);
  // The sum of the efforts whose window holds `now_s`; forgets ended ones.
  double sumAt(double now_s);
  bool empty() const { return entries_.empty(); }

 private:
  struct Entry {
    double effort;
    double start_s;
    double end_s;  // +inf: no end
  };
  std::vector<Entry> entries_;
};

class GazeboServices {
 public:
  // `link` is used for the effort commands and to find the effort controllers.
  GazeboServices(ros::NodeHandle& nh, NodeLink& link, const RobotStateCache& state);
  ~GazeboServices();
  GazeboServices(const GazeboServices&) = delete;
  GazeboServices& operator=(const GazeboServices&) = delete;

 private:
  // The command topic of the running JointEffortController claiming `joint`,
  // or "" (then `why` says what is missing).
  std::string effortTopicFor(const std::string& joint, std::string& why);
  void tick();
  double simTime();

  NodeLink& link_;
  const RobotStateCache& state_;
  std::string model_;
  std::string namespace_;
  std::map<std::string, UrdfJoint> joints_;

  std::mutex controllers_mutex_;
  nlohmann::json controllers_ = nlohmann::json::array();
  std::chrono::steady_clock::time_point controllers_read_{};

  std::mutex mutex_;
  std::map<std::string, EffortSchedule> schedules_;  // by command topic
  std::map<std::string, double> published_;          // the last sum sent per command topic
  std::vector<ros::ServiceServer> servers_;
  std::atomic<bool> stop_{false};
  std::thread ticker_;
};

}  // namespace servoloop::ros1
