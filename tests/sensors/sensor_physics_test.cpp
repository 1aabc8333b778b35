// IMUs and force-torque sensors on bullet and mujoco, each against a
// closed-form reference:
//  - a pendulum held at rest at several angles: the IMU reads the link's
//    orientation, no rotation and +g "up" in its own axes; the force-torque
//    sensor in the hinge reads the link's weight and its moment about the
//    hinge, in the child frame, the parent frame and a turned sensor frame;
//  - the pendulum swinging freely: the IMU (mounted between hinge and centre
//    of mass) reads centripetal and tangential acceleration from the
//    equation of motion, the hinge transmits m·(a_com - g) and no torque;
//  - free fall: the accelerometer reads 0;
//  - a static two-link arm: the shoulder carries the weight of both links,
//    the elbow that of the forearm, each with its moment; a fixed wrist
//    (mujoco) that of the hand, and bullet's clear refusal of it;
//  - seeded noise: the declared standard deviation, the same after a reset;
//    a sensor's update rate holds its samples between updates;
//  - a box resting on the ground with a contact sensor: the contact forces
//    add up to its weight, pushing up, at the ground, named as Gazebo names
//    the ground's collision.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "bullet_robot_hw.hpp"
#include "servoloop/hardware_interface/contact_sensor_interface.hpp"
#include "servoloop/hardware_interface/force_torque_sensor_interface.hpp"
#include "servoloop/hardware_interface/imu_sensor_interface.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/core/errors.hpp"
#include "sim_test_support.hpp"
#ifdef SERVOLOOP_TEST_MUJOCO
#include "mujoco_robot_hw.hpp"
#endif

namespace servoloop::sensor_test {
namespace {

namespace hi = hardware_interface;

constexpr double kG = 9.81;
constexpr double kDt = 0.001;
constexpr double kMass = 2.0;       // kg, the pendulum's rod
constexpr double kComDepth = 0.5;   // m below the hinge
constexpr double kIyy = kMass * 1.0 / 12.0;  // about its centre of mass: a 1 m rod
constexpr double kImuDepth = 0.25;  // m below the hinge

// A rod hanging from a hinge about y, 2 m above the (absent) ground, with an
// IMU between hinge and centre of mass and three force-torque sensors on the
// hinge.
std::string pendulumUrdf(const std::string& imu_extra = "", const std::string& imu_rate = "") {
  return R"(<robot name="pendulum">
  <link name="world"/>
  <joint name="mount" type="fixed"><parent link="world"/><child link="base"/><origin xyz="0 0 2"/></joint>
  <link name="base"/>
  <joint name="hinge" type="continuous">
    <parent link="base"/><child link="rod"/><axis xyz="0 1 0"/>
  </joint>
  <link name="rod">
    <inertial><origin xyz="0 0 -0.5"/><mass value="2"/>
      <inertia ixx="0.1666666666666667" iyy="0.1666666666666667" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <gazebo reference="rod">
    <sensor name="imu" type="imu"><pose>0 0 -0.25 0 0 0</pose>)" +
         imu_rate + imu_extra + R"(</sensor>
  </gazebo>
  <gazebo reference="hinge">
    <sensor name="ft_child" type="force_torque"/>
    <sensor name="ft_parent" type="force_torque">
      <force_torque><frame>parent</frame><measure_direction>parent_to_child</measure_direction></force_torque>
    </sensor>
    <sensor name="ft_turned" type="force_torque"><pose>0 0 0 0 0 1.5707963267948966</pose>
      <force_torque><frame>sensor</frame></force_torque>
    </sensor>
  </gazebo>
</robot>)";
}

constexpr const char* kNoGround = "{sim: {ground_plane: false}}";

template <class Backend>
std::unique_ptr<sim_common::SimRobotHW> makeRobot(const std::string& urdf, const std::string& yaml = kNoGround) {
  auto hw = std::make_unique<Backend>();
  hw->init(sim_testing::makeInfo(urdf, yaml));
  return hw;
}

using RobotFactory = std::unique_ptr<sim_common::SimRobotHW> (*)(const std::string&, const std::string&);

struct Engine {
  std::string name;
  RobotFactory make;
};

std::vector<Engine> engines() {
  std::vector<Engine> out{{"bullet", &makeRobot<sim_bullet::BulletRobotHW>}};
#ifdef SERVOLOOP_TEST_MUJOCO
  out.push_back({"mujoco", &makeRobot<sim_mujoco::MujocoRobotHW>});
#endif
  return out;
}

Eigen::Vector3d vec(const double* v) { return Eigen::Vector3d(v[0], v[1], v[2]); }
Eigen::Matrix3d rotY(double angle) { return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).toRotationMatrix(); }

// A robot whose joints take effort commands, cycled as the control loop does.
class Rig {
 public:
  Rig(const Engine& engine, const std::string& urdf, const std::vector<std::string>& joints,
      const std::string& yaml = kNoGround)
      : hw_(engine.make(urdf, yaml)) {
    std::set<std::string> claimed(joints.begin(), joints.end());
    hw_->doSwitch({sim_testing::controllerClaiming("effort", "EffortJointInterface", claimed)}, {});
    for (const std::string& joint : joints) joints_.push_back(hw_->get<hi::EffortJointInterface>()->getHandle(joint));
  }

  sim_common::SimRobotHW& hw() { return *hw_; }
  hi::JointHandle& joint(std::size_t j) { return joints_[j]; }

  // Efforts for the next step, the step, and the read that shows it.
  void cycle(const std::vector<double>& efforts) {
    for (std::size_t j = 0; j < joints_.size(); ++j) joints_[j].setCommand(efforts[j]);
    hw_->write(Time(), Duration(kDt));
    hw_->step();
    hw_->read(Time(), Duration(kDt));
  }

  hi::ImuSensorHandle imu(const std::string& name) { return hw_->get<hi::ImuSensorInterface>()->getHandle(name); }
  hi::ForceTorqueSensorHandle ft(const std::string& name) {
    return hw_->get<hi::ForceTorqueSensorInterface>()->getHandle(name);
  }

 private:
  std::unique_ptr<sim_common::SimRobotHW> hw_;
  std::vector<hi::JointHandle> joints_;
};

class Sensors : public ::testing::TestWithParam<Engine> {};

TEST_P(Sensors, PendulumAtRestAtSeveralAngles) {
  for (const double angle : {0.0, 0.4, -1.0, 2.0}) {
    SCOPED_TRACE("angle " + std::to_string(angle));
    Rig rig(GetParam(), pendulumUrdf(), {"hinge"});
    rig.hw().setJointPositions({"hinge"}, {angle});
    rig.hw().read(Time(), Duration(kDt));
    // Gravity's moment about the hinge, -m g d sin(angle), held by the hinge's effort.
    const double hold = kMass * kG * kComDepth * std::sin(angle);
    for (int k = 0; k < 20; ++k) rig.cycle({hold});
    EXPECT_NEAR(rig.joint(0).getPosition(), angle, 1e-6) << "held at rest";

    const Eigen::Matrix3d world_from_rod = rotY(angle);
    const hi::ImuSensorHandle imu = rig.imu("imu");
    const Eigen::Quaterniond q(imu.getOrientation()[3], imu.getOrientation()[0], imu.getOrientation()[1],
                               imu.getOrientation()[2]);
    EXPECT_LT(Eigen::AngleAxisd(q.toRotationMatrix().transpose() * world_from_rod).angle(), 1e-6);
    EXPECT_LT(vec(imu.getAngularVelocity()).norm(), 1e-6);
    const Eigen::Vector3d up_in_rod = world_from_rod.transpose() * Eigen::Vector3d(0, 0, kG);
    EXPECT_LT((vec(imu.getLinearAcceleration()) - up_in_rod).norm(), 1e-4)
        << vec(imu.getLinearAcceleration()).transpose() << " vs " << up_in_rod.transpose();

    // The rod's weight and its moment about the hinge; the child applies them to the parent.
    const Eigen::Vector3d weight_world(0, 0, -kMass * kG);
    const Eigen::Vector3d com_world = world_from_rod * Eigen::Vector3d(0, 0, -kComDepth);
    const Eigen::Vector3d moment_world = com_world.cross(weight_world);
    const hi::ForceTorqueSensorHandle child = rig.ft("ft_child");
    EXPECT_EQ(child.getFrameId(), "rod");
    EXPECT_LT((vec(child.getForce()) - world_from_rod.transpose() * weight_world).norm(), 1e-4);
    EXPECT_LT((vec(child.getTorque()) - world_from_rod.transpose() * moment_world).norm(), 1e-4);
    // parent_to_child in the parent's (world-aligned) axes: the opposite.
    const hi::ForceTorqueSensorHandle parent = rig.ft("ft_parent");
    EXPECT_LT((vec(parent.getForce()) + weight_world).norm(), 1e-4);
    EXPECT_LT((vec(parent.getTorque()) + moment_world).norm(), 1e-4);
    // A sensor frame turned 90° about z from the child frame.
    const Eigen::Matrix3d sensor_from_rod =
        Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix().transpose();
    const hi::ForceTorqueSensorHandle turned = rig.ft("ft_turned");
    EXPECT_LT((vec(turned.getForce()) - sensor_from_rod * world_from_rod.transpose() * weight_world).norm(), 1e-4);
    EXPECT_LT((vec(turned.getTorque()) - sensor_from_rod * world_from_rod.transpose() * moment_world).norm(), 1e-4);
  }
}

// Released at 1 rad, no effort: θ'' = -m g d sin θ / I about the hinge. In
// the rod's axes a point at depth s has acceleration (-s θ'', 0, s θ'²)
// (tangential, centripetal), so the accelerometer at s reads that minus
// gravity, (-s θ'' - g sin θ, 0, s θ'² + g cos θ).
TEST_P(Sensors, SwingingPendulum) {
  Rig rig(GetParam(), pendulumUrdf(), {"hinge"});
  rig.hw().setJointPositions({"hinge"}, {1.0});
  rig.hw().read(Time(), Duration(kDt));
  const double inertia = kIyy + kMass * kComDepth * kComDepth;
  const auto angular_acceleration = [&](double angle) { return -kMass * kG * kComDepth * std::sin(angle) / inertia; };
  double previous_angle = rig.joint(0).getPosition();
  double previous_rate = rig.joint(0).getVelocity();
  double largest_rate = 0.0;
  for (int k = 1; k <= 1500; ++k) {
    rig.cycle({0.0});
    const double angle = rig.joint(0).getPosition();
    const double rate = rig.joint(0).getVelocity();
    largest_rate = std::max(largest_rate, std::abs(rate));
    if (k % 50 == 0) {
      SCOPED_TRACE("step " + std::to_string(k));
      const hi::ImuSensorHandle imu = rig.imu("imu");
      EXPECT_LT((vec(imu.getAngularVelocity()) - Eigen::Vector3d(0, rate, 0)).norm(), 1e-9);
      const Eigen::Vector3d expected(-kImuDepth * angular_acceleration(angle) - kG * std::sin(angle), 0,
                                     kImuDepth * rate * rate + kG * std::cos(angle));
      EXPECT_LT((vec(imu.getLinearAcceleration()) - expected).norm(), 0.02)
          << vec(imu.getLinearAcceleration()).transpose() << " vs " << expected.transpose();
      // The hinge's wrench during the last step: m (a_com - g) on the rod from
      // the base, no moment about the free hinge. An engine takes it at the
      // step's start (mujoco) or as the step's mean (bullet): it lies between
      // the values of the step's start and end.
      const auto com_specific_force = [&](double a, double w) {
        return Eigen::Vector3d(-kComDepth * angular_acceleration(a) - kG * std::sin(a), 0,
                               kComDepth * w * w + kG * std::cos(a));
      };
      const Eigen::Vector3d at_start = -kMass * com_specific_force(previous_angle, previous_rate);
      const Eigen::Vector3d at_end = -kMass * com_specific_force(angle, rate);
      const hi::ForceTorqueSensorHandle child = rig.ft("ft_child");
      EXPECT_LT((vec(child.getForce()) - 0.5 * (at_start + at_end)).norm(), 1e-3 + 0.5 * (at_end - at_start).norm())
          << vec(child.getForce()).transpose() << " between " << at_start.transpose() << " and " << at_end.transpose();
      EXPECT_LT(vec(child.getTorque()).norm(), 1e-3) << vec(child.getTorque()).transpose();
    }
    previous_angle = angle;
    previous_rate = rate;
  }
  EXPECT_GT(largest_rate, 3.0) << "the pendulum swung";
}

TEST_P(Sensors, AccelerometerReadsNothingInFreeFall) {
  const std::string urdf = R"(<robot name="box">
  <link name="box">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <gazebo reference="box"><sensor name="imu" type="imu"><pose>0.1 0 0 0 0.3 0</pose></sensor></gazebo>
</robot>)";
  Rig rig(GetParam(), urdf, {});
  for (int k = 0; k < 200; ++k) rig.cycle({});
  const hi::ImuSensorHandle imu = rig.imu("imu");
  EXPECT_LT(vec(imu.getLinearAcceleration()).norm(), 1e-6) << vec(imu.getLinearAcceleration()).transpose();
  EXPECT_LT(vec(imu.getAngularVelocity()).norm(), 1e-9);
}

// Two links of 1 m along x from a shoulder and an elbow (both about y),
// held still by the efforts statics gives: each joint carries the weight of
// the links beyond it and their moment about the joint.
TEST_P(Sensors, StaticArmCarriesTheWeightBelowEachJoint) {
  const std::string urdf = R"(<robot name="arm">
  <link name="world"/>
  <joint name="mount" type="fixed"><parent link="world"/><child link="base"/><origin xyz="0 0 2"/></joint>
  <link name="base"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="1000" velocity="10"/></joint>
  <link name="upper">
    <inertial><origin xyz="0.5 0 0"/><mass value="3"/><inertia ixx="0.01" iyy="0.25" izz="0.25" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/><origin xyz="1 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="1000" velocity="10"/></joint>
  <link name="fore">
    <inertial><origin xyz="0.5 0 0"/><mass value="1.5"/><inertia ixx="0.01" iyy="0.125" izz="0.125" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <gazebo reference="shoulder"><sensor name="shoulder_ft" type="force_torque"/></gazebo>
  <gazebo reference="elbow"><sensor name="elbow_ft" type="force_torque"/></gazebo>
</robot>)";
  const double q1 = -0.3;  // the upper arm 0.3 rad above horizontal
  const double q2 = 0.9;
  Rig rig(GetParam(), urdf, {"shoulder", "elbow"});
  rig.hw().setJointPositions({"shoulder", "elbow"}, {q1, q2});
  rig.hw().read(Time(), Duration(kDt));
  // Link frames: rotation about y by q; a point (x, 0, 0) of the upper arm is at
  // (x cos q1, 0, -x sin q1).
  const Eigen::Matrix3d upper_rot = rotY(q1);
  const Eigen::Matrix3d fore_rot = rotY(q1 + q2);
  const Eigen::Vector3d elbow_at = upper_rot * Eigen::Vector3d(1, 0, 0);
  const Eigen::Vector3d upper_com = upper_rot * Eigen::Vector3d(0.5, 0, 0);
  const Eigen::Vector3d fore_com = elbow_at + fore_rot * Eigen::Vector3d(0.5, 0, 0);
  const Eigen::Vector3d g(0, 0, -kG);
  // Moments of gravity about each joint; the joints' efforts cancel their y parts.
  const Eigen::Vector3d elbow_moment = (fore_com - elbow_at).cross(1.5 * g);
  const Eigen::Vector3d shoulder_moment = upper_com.cross(3.0 * g) + fore_com.cross(1.5 * g);
  for (int k = 0; k < 20; ++k) rig.cycle({-shoulder_moment.y(), -elbow_moment.y()});
  EXPECT_NEAR(rig.joint(0).getPosition(), q1, 1e-6);
  EXPECT_NEAR(rig.joint(1).getPosition(), q2, 1e-6);

  const hi::ForceTorqueSensorHandle shoulder = rig.ft("shoulder_ft");
  EXPECT_LT((vec(shoulder.getForce()) - upper_rot.transpose() * (4.5 * g)).norm(), 1e-4)
      << vec(shoulder.getForce()).transpose();
  EXPECT_LT((vec(shoulder.getTorque()) - upper_rot.transpose() * shoulder_moment).norm(), 1e-4)
      << vec(shoulder.getTorque()).transpose() << " vs " << (upper_rot.transpose() * shoulder_moment).transpose();
  const hi::ForceTorqueSensorHandle elbow = rig.ft("elbow_ft");
  EXPECT_LT((vec(elbow.getForce()) - fore_rot.transpose() * (1.5 * g)).norm(), 1e-4);
  EXPECT_LT((vec(elbow.getTorque()) - fore_rot.transpose() * elbow_moment).norm(), 1e-4);
}

// A wrist sensor in a fixed joint (the usual place of a force-torque
// sensor): mujoco keeps the hand a body of its own and measures what the
// joint holds; bullet merges the hand into the arm and says so.
TEST_P(Sensors, ForceTorqueSensorInAFixedWrist) {
  const std::string urdf = R"(<robot name="arm">
  <link name="world"/>
  <joint name="mount" type="fixed"><parent link="world"/><child link="base"/><origin xyz="0 0 2"/></joint>
  <link name="base"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="1000" velocity="10"/></joint>
  <link name="upper">
    <inertial><origin xyz="0.5 0 0"/><mass value="3"/><inertia ixx="0.01" iyy="0.25" izz="0.25" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="wrist" type="fixed"><parent link="upper"/><child link="hand"/><origin xyz="1 0 0"/></joint>
  <link name="hand">
    <inertial><origin xyz="0.1 0 0"/><mass value="0.5"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <gazebo reference="wrist"><sensor name="wrist_ft" type="force_torque"/></gazebo>
</robot>)";
  if (GetParam().name == "bullet") {
    try {
      Rig rig(GetParam(), urdf, {"shoulder"});
      FAIL() << "bullet cannot measure a fixed joint";
    } catch (const ConfigError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("wrist_ft"), std::string::npos) << message;
      EXPECT_NE(message.find("'wrist' is not a movable joint"), std::string::npos) << message;
      EXPECT_NE(message.find("mujoco"), std::string::npos) << message;
    }
    return;
  }
  const double q = -0.4;
  Rig rig(GetParam(), urdf, {"shoulder"});
  rig.hw().setJointPositions({"shoulder"}, {q});
  rig.hw().read(Time(), Duration(kDt));
  const Eigen::Matrix3d rot = rotY(q);
  const Eigen::Vector3d g(0, 0, -kG);
  const Eigen::Vector3d wrist_at = rot * Eigen::Vector3d(1, 0, 0);
  const Eigen::Vector3d hand_com = rot * Eigen::Vector3d(1.1, 0, 0);
  const Eigen::Vector3d upper_com = rot * Eigen::Vector3d(0.5, 0, 0);
  const double hold = -(upper_com.cross(3.0 * g) + hand_com.cross(0.5 * g)).y();
  for (int k = 0; k < 20; ++k) rig.cycle({hold});
  ASSERT_NEAR(rig.joint(0).getPosition(), q, 1e-6);
  const hi::ForceTorqueSensorHandle wrist = rig.ft("wrist_ft");
  EXPECT_EQ(wrist.getFrameId(), "hand");
  EXPECT_LT((vec(wrist.getForce()) - rot.transpose() * (0.5 * g)).norm(), 1e-4);
  EXPECT_LT((vec(wrist.getTorque()) - rot.transpose() * (hand_com - wrist_at).cross(0.5 * g)).norm(), 1e-4)
      << vec(wrist.getTorque()).transpose();
}

TEST_P(Sensors, NoiseHasTheDeclaredSpreadAndRepeatsAfterReset) {
  const std::string noise = R"(<imu><angular_velocity><x><noise type="gaussian"><mean>0</mean><stddev>0.01</stddev></noise></x></angular_velocity>
    <linear_acceleration><z><noise type="gaussian"><mean>0.5</mean><stddev>0.2</stddev></noise></z></linear_acceleration></imu>)";
  Rig rig(GetParam(), pendulumUrdf(noise), {"hinge"});
  const int samples = 4000;
  std::vector<double> gyro_x;
  std::vector<double> accel_z;
  for (int k = 0; k < samples; ++k) {
    rig.cycle({0.0});  // hanging straight down, at rest
    gyro_x.push_back(rig.imu("imu").getAngularVelocity()[0]);
    accel_z.push_back(rig.imu("imu").getLinearAcceleration()[2]);
  }
  const auto mean = [](const std::vector<double>& v) {
    double sum = 0.0;
    for (const double x : v) sum += x;
    return sum / static_cast<double>(v.size());
  };
  const auto stddev = [&](const std::vector<double>& v) {
    const double m = mean(v);
    double sum = 0.0;
    for (const double x : v) sum += (x - m) * (x - m);
    return std::sqrt(sum / static_cast<double>(v.size() - 1));
  };
  // 4000 samples: the sample deviation is within ~2.2 % (1σ) of the true one.
  EXPECT_NEAR(stddev(gyro_x), 0.01, 0.01 * 0.08);
  EXPECT_NEAR(mean(gyro_x), 0.0, 4 * 0.01 / std::sqrt(samples));
  EXPECT_NEAR(stddev(accel_z), 0.2, 0.2 * 0.08);
  EXPECT_NEAR(mean(accel_z), kG + 0.5, 4 * 0.2 / std::sqrt(samples));
  EXPECT_EQ(rig.imu("imu").getAngularVelocityCovariance()[0], 0.01 * 0.01);
  EXPECT_EQ(rig.imu("imu").getLinearAccelerationCovariance()[8], 0.2 * 0.2);

  rig.hw().reset();
  for (int k = 0; k < 100; ++k) {
    rig.cycle({0.0});
    ASSERT_EQ(rig.imu("imu").getAngularVelocity()[0], gyro_x[static_cast<std::size_t>(k)]) << "sample " << k;
  }
}

TEST_P(Sensors, UpdateRateHoldsSamplesBetweenUpdates) {
  const std::string noise = R"(<imu><angular_velocity><x><noise type="gaussian"><stddev>0.01</stddev></noise></x></angular_velocity></imu>)";
  Rig rig(GetParam(), pendulumUrdf(noise, "<update_rate>100</update_rate>"), {"hinge"});
  int changes = 0;
  double last = rig.imu("imu").getAngularVelocity()[0];
  for (int k = 0; k < 1000; ++k) {
    rig.cycle({0.0});
    const double now = rig.imu("imu").getAngularVelocity()[0];
    changes += now != last;
    last = now;
  }
  EXPECT_EQ(changes, 100) << "100 Hz on a 1 kHz step: one new sample every 10 steps";
}

TEST_P(Sensors, ContactSensorOfABoxOnTheGroundCarriesItsWeight) {
  const std::string urdf = R"(<robot name="crate">
  <link name="crate">
    <inertial><mass value="1.5"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <gazebo reference="crate">
    <sensor name="bumper" type="contact">
      <update_rate>50</update_rate>
      <contact><collision>crate_collision</collision></contact>
      <plugin name="bumper_plugin" filename="libgazebo_ros_bumper.so"><bumperTopicName>crate_bumper</bumperTopicName></plugin>
    </sensor>
  </gazebo>
</robot>)";
  Rig rig(GetParam(), urdf, {}, "{sim: {ground_plane: true, pose: [0, 0, 0.1005, 0, 0, 0]}}");
  for (int k = 0; k < 1000; ++k) rig.cycle({});  // settled
  const hi::ContactSensorHandle bumper = rig.hw().get<hi::ContactSensorInterface>()->getHandle("bumper");
  EXPECT_EQ(bumper.getTopic(), "crate_bumper");
  EXPECT_EQ(bumper.getFrameId(), "world");
  EXPECT_EQ(bumper.getCollision(), "crate::crate::crate_collision");
  const hi::ContactSensorReading& reading = bumper.getReading();
  ASSERT_GE(reading.count, 1u);
  EXPECT_EQ(reading.dropped, 0u);
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < reading.count; ++k) {
    const hi::ContactPoint& point = reading.points[k];
    EXPECT_STREQ(point.other_collision.data(), "ground_plane::link::collision");
    EXPECT_NEAR(point.position[2], 0.0, 2e-3) << "on the ground";
    EXPECT_LT((vec(point.normal) - Eigen::Vector3d::UnitZ()).norm(), 1e-6) << "the ground pushes up";
    EXPECT_GE(point.depth, 0.0);
    total += vec(point.force);
  }
  EXPECT_LT((total - Eigen::Vector3d(0, 0, 1.5 * kG)).norm(), 1e-3 * 1.5 * kG)
      << total.transpose() << " over " << reading.count << " point(s)";
}

INSTANTIATE_TEST_SUITE_P(Engines, Sensors, ::testing::ValuesIn(engines()),
                         [](const ::testing::TestParamInfo<Engine>& info) { return info.param.name; });

}  // namespace
}  // namespace servoloop::sensor_test
