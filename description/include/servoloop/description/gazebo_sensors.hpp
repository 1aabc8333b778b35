#pragma once
// The sensors a URDF declares for Gazebo, in its <gazebo reference="..."> blocks:
//
//   <gazebo reference="LINK"><sensor name="imu" type="imu"> ... </sensor></gazebo>
//   <gazebo reference="JOINT"><sensor name="ft" type="force_torque"> ... </sensor></gazebo>
//   <gazebo reference="LINK"><sensor name="bumper" type="contact">
//     <contact><collision>LINK_collision</collision></contact> ... </sensor></gazebo>
//
// and the gazebo_ros plugins that give the same sensors with their topics:
// gazebo_ros_imu_sensor, gazebo_ros_ft_sensor and gazebo_ros_bumper inside a
// <sensor>, and the model plugins gazebo_ros_imu, hector_gazebo_ros_imu (an IMU
// on <bodyName>) and gazebo_ros_ft_sensor (a force-torque sensor on
// <jointName>) in a <gazebo> block without reference, each named after the
// plugin's name attribute. The forms of Gazebo before 1.0 (PR2's URDF) are read
// too: <sensor:contact name="..."><geom>...</geom> with a
// <controller:gazebo_ros_bumper plugin="libgazebo_ros_bumper.so"> inside, and
// <controller:gazebo_ros_imu plugin="libgazebo_ros_imu.so"> as a model plugin.
// Non-real-time only (parses, allocates, throws).
#include <array>
#include <string>
#include <vector>

#include <urdf_model/model.h>

namespace servoloop {

enum class SensorType { imu, force_torque, contact };

// "imu", "force_torque" or "contact".
const char* toString(SensorType type) noexcept;

// SDFormat's <noise type="gaussian">: each sample gets mean + N(0, stddev²)
// added, plus a bias drawn once per run from N(bias_mean, bias_stddev²) with
// a random sign. All zero: no noise.
struct GaussianNoise {
  double mean = 0.0;
  double stddev = 0.0;
  double bias_mean = 0.0;
  double bias_stddev = 0.0;

  bool none() const noexcept { return mean == 0.0 && stddev == 0.0 && bias_mean == 0.0 && bias_stddev == 0.0; }
};

// Gazebo's <force_torque><frame>: the axes the wrench is given in, and the
// point the torque is taken about (the origin of that frame).
enum class ForceTorqueFrame { child, parent, sensor };
// Gazebo's <force_torque><measure_direction>: child_to_parent gives the wrench
// the child link applies to the parent; parent_to_child the opposite.
enum class ForceTorqueDirection { child_to_parent, parent_to_child };

struct SensorDescription {
  std::string name;  // <sensor name>, unique within the robot
  SensorType type = SensorType::imu;
  // The link the sensor is on (imu, contact), or the joint it measures
  // (force_torque), as the URDF names it.
  std::string reference;
  // For error messages: where the sensor is declared, e.g.
  // "robot.urdf: <gazebo reference='imu_link'><sensor name='imu'>".
  std::string element;
  // <update_rate>, else the plugin's updateRate/updateRateHZ, Hz; 0: every
  // physics step.
  double update_rate_hz = 0.0;
  bool always_on = true;
  // <pose> (a model plugin's xyzOffset and rpyOffset): x y z roll pitch yaw
  // of the sensor frame in the reference link's frame (force_torque: in the
  // joint's child link frame, the joint frame).
  std::array<double, 6> pose{};
  // Topic the gazebo_ros plugin publishes on (topicName, bumperTopicName),
  // relative to the robot's namespace; "" without a plugin or without a
  // topic in it: the caller uses the sensor's name.
  std::string topic;
  // header.frame_id of the messages: the plugin's frameName, else the
  // reference link (force_torque: the joint's child link; contact: "world",
  // gazebo_ros_bumper's default, whose values are in the world frame).
  std::string frame_id;

  // imu: noise per axis (x, y, z) of the angular velocity (rad/s) and the
  // linear acceleration (m/s²), and of the orientation (rad, each axis), as
  // <imu><angular_velocity><x><noise> ... or a plugin's gaussianNoise give it.
  // gazebo_ros_imu_sensor's and gazebo_ros_imu's gaussianNoise is the stddev
  // of all three on every axis (of the angular velocity or linear
  // acceleration only where <imu> gives that one no <noise>);
  // hector_gazebo_ros_imu's rateGaussianNoise and accelGaussianNoise (and
  // its gaussianNoise, when not 0, for both) are those of the angular
  // velocity and linear acceleration.
  std::array<GaussianNoise, 3> angular_velocity_noise{};
  std::array<GaussianNoise, 3> linear_acceleration_noise{};
  GaussianNoise orientation_noise{};

  // force_torque.
  ForceTorqueFrame frame = ForceTorqueFrame::child;
  ForceTorqueDirection measure_direction = ForceTorqueDirection::child_to_parent;
  GaussianNoise wrench_noise{};  // gazebo_ros_ft_sensor's gaussianNoise, on every component

  // contact: the <contact><collision> names as written (Gazebo's names for
  // the link's collisions, e.g. "bumper_link_collision", or
  // "base_link_fixed_joint_lump__bumper_link_collision" once a fixed joint
  // merges bumper_link into base_link); the sensor reports every contact of
  // the reference link's collision geometry.
  std::vector<std::string> collisions;
};

// Reads every sensor of `urdf_xml` (the URDF text `model` was parsed from).
// `source_name` names the file in errors. Gazebo sensor types servoloop does
// not simulate (camera, depth, ray, gpu_ray, gps, ...) are left out with one
// warning each.
//
// Throws servoloop::ConfigError, naming the file, the element and the fix,
// for: a reference (or <bodyName>, <jointName>) that names no link (imu,
// contact) or no joint (force_torque) of the model (a link the model left
// out, e.g. a massless one, is named as such); a sensor without a name, or
// two sensors of one robot with the same name; a type Gazebo does not know
// (the message lists the types); an unknown <force_torque><frame> or
// <measure_direction>, or <noise type>; a negative, infinite or non-numeric
// update rate, noise stddev or bias stddev (or a non-numeric mean); a
// <pose> that is not 6 numbers, or an offset not 3; an <always_on> that is
// not true, false, 1 or 0; a contact sensor without <contact><collision>,
// or one naming a collision of another link.
std::vector<SensorDescription> readGazeboSensors(const std::string& urdf_xml, const urdf::ModelInterface& model,
                                                 const std::string& source_name);

}  // namespace servoloop
