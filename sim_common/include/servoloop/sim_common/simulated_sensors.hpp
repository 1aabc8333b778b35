#pragma once
// The IMUs and force-torque sensors of a simulated robot, as its URDF's
// <gazebo> blocks declare them (description/gazebo_sensors.hpp), read from
// the physics engine's link states and joint wrenches:
//
//   IMU: the sensor frame (the link frame moved by the sensor's <pose>) in
//        the world: orientation (sensor -> world, REP 145's world
//        reference, as gazebo_ros_imu_sensor gives it), angular velocity and
//        specific force in the sensor's axes. The specific force is the
//        acceleration of the sensor's origin, by the difference of its
//        velocity since the last read, minus gravity: +g upwards at rest, 0
//        in free fall, as a real accelerometer (and Gazebo's ImuSensor).
//   force-torque: the wrench the joint transmits, the torque about the
//        joint origin, in the child link's, the parent link's or the
//        sensor's axes (<frame>), as the child applies it to the parent
//        (child_to_parent, Gazebo's default) or the opposite.
//   contact: the contact points of the link's collision geometry with
//        anything else during the last step, world frame, each with the
//        other collision's scoped name (ContactSensorInterface).
//
// Noise as SDFormat's Gaussian model: per sample mean + N(0, stddev²), plus
// a bias drawn once per run (and after each reset) from
// N(bias_mean, bias_stddev²) with a random sign. Each sensor has its own
// generator seeded from its name, so reruns and resets repeat the same
// noise. The orientation's noise turns it by a small rotation with that
// standard deviation per axis. Each covariance is diag(stddev²).
// A sensor with an update rate keeps its last sample until the next is due.
// IMU and force-torque handles are named after the topic of the sensor's
// gazebo_ros plugin (topicName), so ros_controllers' sensor controllers,
// which publish on <ns>/<handle name>, publish where Gazebo would; a sensor
// without a plugin topic is named after itself.
//
// Threading: init(), registerInterfaces() and reset() are non-real-time;
// update() runs on the real-time thread (no allocation, no locks, no throw).
#include <array>
#include <cstddef>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <urdf_model/model.h>

#include "servoloop/description/gazebo_sensors.hpp"
#include "servoloop/hardware_interface/contact_sensor_interface.hpp"
#include "servoloop/hardware_interface/force_torque_sensor_interface.hpp"
#include "servoloop/hardware_interface/imu_sensor_interface.hpp"
#include "servoloop/hardware_interface/interface_manager.hpp"
#include "servoloop/sim_common/physics_engine.hpp"

namespace servoloop::sim_common {

class SimulatedSensors {
 public:
  // Non-real-time, after the engine's init(): the sensors' links and joints
  // tracked in `engine`, their storage sized. `gravity` is the world's
  // (m/s², world frame). Throws servoloop::ConfigError naming the sensor
  // when the engine cannot give what it needs.
  void init(const std::vector<SensorDescription>& sensors, const urdf::ModelInterface& model, PhysicsEngine& engine,
            const Eigen::Vector3d& gravity, const std::string& source_name);
  // Non-real-time: ImuSensorInterface, ForceTorqueSensorInterface and
  // ContactSensorInterface offered by `hardware` when the robot has such
  // sensors.
  void registerInterfaces(hardware_interface::InterfaceManager& hardware);
  // Non-real-time: noise generators and biases restarted, the last samples
  // and velocities forgotten (then one update()).
  void reset(double time_s) noexcept;
  // Real-time: reads the engine after a step; `time_s` is the simulated time.
  void update(double time_s) noexcept;
  // True when the robot has no sensor: update() then has nothing to do.
  bool empty() const noexcept { return imus_.empty() && force_torques_.empty() && contacts_.empty(); }

  std::size_t imuCount() const noexcept { return imus_.size(); }
  std::size_t forceTorqueCount() const noexcept { return force_torques_.size(); }
  std::size_t contactCount() const noexcept { return contacts_.size(); }

 private:
  struct Noise {
    GaussianNoise model;
    double bias = 0.0;
  };
  struct Sampling {
    double period_s = 0.0;  // 0: every update
    double next_s = 0.0;
    bool due(double time_s) noexcept;
  };
  struct Imu {
    std::string name;
    std::string frame_id;
    std::size_t link = 0;  // engine's tracked link
    Eigen::Isometry3d sensor_in_link{Eigen::Isometry3d::Identity()};
    Sampling sampling;
    std::mt19937_64 generator;
    std::normal_distribution<double> unit;
    std::uint64_t seed = 0;
    std::array<Noise, 3> angular_velocity_noise;
    std::array<Noise, 3> linear_acceleration_noise;
    std::array<Noise, 3> orientation_noise;
    Eigen::Vector3d last_velocity{Eigen::Vector3d::Zero()};  // of the sensor's origin, world
    double last_time_s = 0.0;
    bool has_last = false;
    // What the handle points to.
    std::array<double, 4> orientation{0.0, 0.0, 0.0, 1.0};
    std::array<double, 9> orientation_covariance{};
    std::array<double, 3> angular_velocity{};
    std::array<double, 9> angular_velocity_covariance{};
    std::array<double, 3> linear_acceleration{};
    std::array<double, 9> linear_acceleration_covariance{};
  };
  struct ForceTorque {
    std::string name;
    std::string frame_id;
    std::size_t joint = 0;         // engine's tracked joint
    std::size_t child_link = 0;    // engine's tracked links (frame parent only)
    std::size_t parent_link = 0;
    ForceTorqueFrame frame = ForceTorqueFrame::child;
    double sign = -1.0;  // child_to_parent: minus what the parent applies to the child
    Eigen::Matrix3d sensor_from_child{Eigen::Matrix3d::Identity()};
    Sampling sampling;
    std::mt19937_64 generator;
    std::normal_distribution<double> unit;
    std::uint64_t seed = 0;
    Noise noise;
    std::array<double, 3> force{};
    std::array<double, 3> torque{};
  };

  struct Contact {
    std::string name;
    std::string frame_id;
    std::string collision;  // "robot::link::link_collision"
    std::string topic;
    double update_rate_hz = 0.0;
    std::size_t tracked = 0;  // engine's tracked contacts
    std::size_t link = 0;     // engine's tracked link (the torques' point)
    Sampling sampling;
    std::vector<EngineContact> scratch;  // sized once: the reading's capacity
    hardware_interface::ContactSensorReading reading;
  };

  void sampleImu(Imu& imu, double time_s) noexcept;
  void sampleContacts(Contact& sensor) noexcept;
  void sampleForceTorque(ForceTorque& sensor) noexcept;

  PhysicsEngine* engine_ = nullptr;
  Eigen::Vector3d gravity_{0.0, 0.0, -9.81};
  std::vector<Imu> imus_;
  std::vector<ForceTorque> force_torques_;
  std::vector<Contact> contacts_;
  hardware_interface::ImuSensorInterface imu_interface_;
  hardware_interface::ForceTorqueSensorInterface force_torque_interface_;
  hardware_interface::ContactSensorInterface contact_interface_;
};

}  // namespace servoloop::sim_common
