#pragma once
// Gazebo's model services, answered by the node's model.* operations
// (docs/node_operations.md) for every model of the node's world, not only
// the bridged robot:
//
//   /gazebo/get_model_state    a model's pose and twist in the world frame
//                              (model.get): a floating base's ground truth,
//                              a fixed base's spawn pose;
//   /gazebo/set_model_state    a floating base teleported and set moving
//                              (model.set_state), pose and twist both, as
//                              Gazebo sets them; reference_frame must be the
//                              world ("", "world", "map");
//   /gazebo/spawn_urdf_model   a model from URDF text (model.spawn, through a
//                              private temporary file), at initial_pose in
//                              the world frame; what `rosrun gazebo_ros
//                              spawn_model -urdf` calls;
//   /gazebo/delete_model       a model taken out of the world (model.delete).
//
// /gazebo/spawn_sdf_model is not served: servoloop reads URDF only.
//
// A call the node refuses answers success=false with the node's reason in
// status_message, as Gazebo answers a call it cannot carry out.
#include <array>
#include <string>
#include <vector>

#include <ros/node_handle.h>
#include <ros/service_server.h>

#include "node_link.hpp"
#include "robot_state_cache.hpp"

namespace servoloop::ros1 {

// Whether Gazebo takes `frame` for the world frame: "", "world", "map" or
// "/map" (gazebo_ros_api_plugin's test for a reference frame).
bool isWorldFrame(const std::string& frame);

// roll, pitch, yaw (rad) of the quaternion (x, y, z, w) in URDF's convention
// R = Rz(yaw)·Ry(pitch)·Rx(roll). The quaternion is normalised first; the zero
// quaternion (a ROS message's default) is the identity, as Gazebo takes it;
// a quaternion with a NaN or an infinity gives NaN angles.
std::array<double, 3> rollPitchYaw(double x, double y, double z, double w);

class GazeboModelServices {
 public:
  // `state` gives the stamp of get_model_state's header (simulated time).
  GazeboModelServices(ros::NodeHandle& nh, NodeLink& link, const RobotStateCache& state);
  GazeboModelServices(const GazeboModelServices&) = delete;
  GazeboModelServices& operator=(const GazeboModelServices&) = delete;

 private:
  NodeLink& link_;
  const RobotStateCache& state_;
  std::vector<ros::ServiceServer> servers_;
};

}  // namespace servoloop::ros1
