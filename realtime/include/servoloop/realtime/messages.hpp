#pragma once
// The message types carried by the topic bus: plain structs with the field
// names of their ROS counterparts, so `topic echo` output and `topic pub`
// arguments read the way ROS users expect. Each names itself with kTypeName,
// which is what the bus type-checks topics against.
//
// Time stamps are control time in seconds (servoloop::Time::seconds), in
// place of ROS's header.stamp. JSON, text and CSV forms: message_json.hpp.
#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace servoloop {

namespace std_msgs {

struct Float64 {
  static constexpr std::string_view kTypeName = "std_msgs/Float64";
  double data = 0.0;
};

// A switch, e.g. a robot's `estop` input (true: engage the emergency stop).
struct Bool {
  static constexpr std::string_view kTypeName = "std_msgs/Bool";
  bool data = false;
};

// ROS's layout field (dimension labels and strides) is left out: every
// ros_control user of this type reads `data` only.
struct Float64MultiArray {
  static constexpr std::string_view kTypeName = "std_msgs/Float64MultiArray";
  std::vector<double> data;
};

}  // namespace std_msgs

namespace sensor_msgs {

// One entry per joint; position/velocity/effort are either empty or as long
// as name. Units: rad, rad/s, N·m for revolute joints; m, m/s, N for prismatic.
struct JointState {
  static constexpr std::string_view kTypeName = "sensor_msgs/JointState";
  double stamp = 0.0;  // control time, s
  std::vector<std::string> name;
  std::vector<double> position;
  std::vector<double> velocity;
  std::vector<double> effort;
};

}  // namespace sensor_msgs

namespace control_msgs {

// What a PID-driven joint controller reports about its loop (joint space).
struct JointControllerState {
  static constexpr std::string_view kTypeName = "control_msgs/JointControllerState";
  double stamp = 0.0;              // control time, s
  double set_point = 0.0;          // commanded joint position (or velocity)
  double process_value = 0.0;      // measured joint position (or velocity)
  double process_value_dot = 0.0;  // its time derivative
  double error = 0.0;              // set_point - process_value, as the controller computes it
  double time_step = 0.0;          // period of the last update, s
  double command = 0.0;            // joint effort (or velocity) the controller wrote
  double p = 0.0;                  // PID gains in effect
  double i = 0.0;
  double d = 0.0;
  double i_clamp = 0.0;
  bool antiwindup = false;
};

}  // namespace control_msgs

namespace trajectory_msgs {

// One point of a joint trajectory, joints in the order of the trajectory's
// joint_names. velocities, accelerations and effort are either empty or one
// per joint. time_from_start is seconds from the trajectory's start.
struct JointTrajectoryPoint {
  std::vector<double> positions;
  std::vector<double> velocities;
  std::vector<double> accelerations;
  std::vector<double> effort;
  double time_from_start = 0.0;  // s
};

// A trajectory for some joints: the points are reached at stamp +
// time_from_start (stamp is control time; 0 means "when it arrives").
struct JointTrajectory {
  static constexpr std::string_view kTypeName = "trajectory_msgs/JointTrajectory";
  double stamp = 0.0;  // control time, s; 0 = now
  std::vector<std::string> joint_names;
  std::vector<JointTrajectoryPoint> points;
};

}  // namespace trajectory_msgs

namespace control_msgs {

// What a joint trajectory controller reports: for its joints (in the order of
// joint_names), the state it wants now (desired), the state it measures
// (actual) and desired - actual (error; the shortest way round for
// continuous joints). Each point's time_from_start is the time since the
// trajectory started (0 while holding).
struct JointTrajectoryControllerState {
  static constexpr std::string_view kTypeName = "control_msgs/JointTrajectoryControllerState";
  double stamp = 0.0;  // control time, s
  std::vector<std::string> joint_names;
  trajectory_msgs::JointTrajectoryPoint desired;
  trajectory_msgs::JointTrajectoryPoint actual;
  trajectory_msgs::JointTrajectoryPoint error;
};

}  // namespace control_msgs

namespace geometry_msgs {

struct Point {
  double x = 0.0, y = 0.0, z = 0.0;
};
struct Quaternion {
  double x = 0.0, y = 0.0, z = 0.0, w = 1.0;
};
struct Vector3 {
  double x = 0.0, y = 0.0, z = 0.0;
};

// A velocity command: linear in m/s, angular in rad/s (a mobile base's
// cmd_vel; a differential drive reads linear.x and angular.z).
struct Twist {
  static constexpr std::string_view kTypeName = "geometry_msgs/Twist";
  Vector3 linear;
  Vector3 angular;
};

// Where a body is: position (m) and orientation.
struct Pose {
  Point position;
  Quaternion orientation;
};

// Where child_frame_id is in frame_id: translation (m) and rotation.
struct TransformStamped {
  double stamp = 0.0;  // control time, s
  std::string frame_id;
  std::string child_frame_id;
  Vector3 translation;
  Quaternion rotation;
};

// A force (N) and a torque (N·m).
struct Wrench {
  Vector3 force;
  Vector3 torque;
};

// A wrench measured in frame_id, the torque about that frame's origin (a
// force-torque sensor's reading).
struct WrenchStamped {
  static constexpr std::string_view kTypeName = "geometry_msgs/WrenchStamped";
  double stamp = 0.0;  // control time, s
  std::string frame_id;
  Wrench wrench;
};

}  // namespace geometry_msgs

namespace sensor_msgs {

// An IMU's reading in frame_id: orientation, angular velocity (rad/s) and
// linear acceleration (m/s², specific force: +9.81 upwards at rest), each with
// its row-major 3×3 covariance; covariance[0] = -1 says the value is not
// measured, as in ROS.
struct Imu {
  static constexpr std::string_view kTypeName = "sensor_msgs/Imu";
  double stamp = 0.0;  // control time, s
  std::string frame_id;
  geometry_msgs::Quaternion orientation;
  std::array<double, 9> orientation_covariance{};
  geometry_msgs::Vector3 angular_velocity;
  std::array<double, 9> angular_velocity_covariance{};
  geometry_msgs::Vector3 linear_acceleration;
  std::array<double, 9> linear_acceleration_covariance{};
};

}  // namespace sensor_msgs

namespace tf2_msgs {

// The transforms of the /tf topic.
struct TFMessage {
  static constexpr std::string_view kTypeName = "tf2_msgs/TFMessage";
  std::vector<geometry_msgs::TransformStamped> transforms;
};

}  // namespace tf2_msgs

namespace gazebo_msgs {

// Every model of the world with its pose in the world frame and its twist
// (linear velocity of the model frame's origin, angular velocity; world axes),
// as Gazebo publishes them on /gazebo/model_states.
struct ModelStates {
  static constexpr std::string_view kTypeName = "gazebo_msgs/ModelStates";
  std::vector<std::string> name;
  std::vector<geometry_msgs::Pose> pose;
  std::vector<geometry_msgs::Twist> twist;
};

// The contacts between one collision of the sensor and one other collision,
// Gazebo's scoped names ("model::link::collision"): per contact point its
// wrench on collision1, position and normal (frame of the ContactsState),
// and depth (m); total_wrench is their sum.
struct ContactState {
  std::string info;
  std::string collision1_name;
  std::string collision2_name;
  std::vector<geometry_msgs::Wrench> wrenches;
  geometry_msgs::Wrench total_wrench;
  std::vector<geometry_msgs::Vector3> contact_positions;
  std::vector<geometry_msgs::Vector3> contact_normals;
  std::vector<double> depths;
};

// A contact sensor's reading, as gazebo_ros_bumper publishes it.
struct ContactsState {
  static constexpr std::string_view kTypeName = "gazebo_msgs/ContactsState";
  double stamp = 0.0;  // control time, s
  std::string frame_id;
  std::vector<ContactState> states;
};

}  // namespace gazebo_msgs

namespace diagnostic_msgs {

struct KeyValue {
  std::string key;
  std::string value;
};

// One part's health, as ROS's DiagnosticStatus: level kOk, kWarn, kError or
// kStale, a name ("/arm: control loop"), a one-line message and key/values.
struct DiagnosticStatus {
  static constexpr int kOk = 0;
  static constexpr int kWarn = 1;
  static constexpr int kError = 2;
  static constexpr int kStale = 3;
  int level = kOk;
  std::string name;
  std::string message;
  std::string hardware_id;
  std::vector<KeyValue> values;
};

// ROS's /diagnostics message.
struct DiagnosticArray {
  static constexpr std::string_view kTypeName = "diagnostic_msgs/DiagnosticArray";
  double stamp = 0.0;  // control time, s
  std::vector<DiagnosticStatus> status;
};

}  // namespace diagnostic_msgs

namespace nav_msgs {

// Where a body is and how it moves: the pose of child_frame_id in frame_id,
// and its twist in child_frame_id's axes, as ROS's Odometry, with the 6×6
// row-major covariances of (x, y, z, roll, pitch, yaw). m, rad, m/s, rad/s.
struct Odometry {
  static constexpr std::string_view kTypeName = "nav_msgs/Odometry";
  double stamp = 0.0;  // control time, s
  std::string frame_id;
  std::string child_frame_id;
  geometry_msgs::Point position;
  geometry_msgs::Quaternion orientation;
  geometry_msgs::Vector3 linear;   // twist.linear, child frame
  geometry_msgs::Vector3 angular;  // twist.angular, child frame
  std::array<double, 36> pose_covariance{};   // pose.covariance
  std::array<double, 36> twist_covariance{};  // twist.covariance
};

}  // namespace nav_msgs

}  // namespace servoloop
