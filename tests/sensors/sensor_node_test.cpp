// Sensors as users run them, in a node on bullet and mujoco:
//  - the seed robot with an IMU on its moving link and a force-torque sensor
//    in its joint (robots/one_dof/one_dof_sensors.launch.yaml), with
//    ros_controllers' two sensor controllers in its YAML: both load and
//    publish sensor_msgs/Imu and geometry_msgs/WrenchStamped; with the arm
//    held at 1 rad the IMU reads the link's tilt and +g up in its axes, the
//    joint the link's weight and moment (1 kg, centre of mass 0.5 m up);
//  - a box resting on a plate with a contact sensor (another robot): the
//    bumper topic's ContactsState names both collisions and its contacts
//    carry the box's weight, pushing the plate down;
//  - the wheeled base (robots/diff_bot) with an IMU on its base as husky
//    has it (hector_gazebo_ros_imu, topicName imu/data: the controller
//    publishes on /diff_bot/imu/data), driving a circle: the IMU's yaw rate
//    and its centripetal acceleration v·ω match the base's ground truth, and
//    the two engines agree.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "servoloop/node/node.hpp"
#include "servoloop/realtime/messages.hpp"
#include "temp_dir.hpp"

namespace servoloop::sensor_test {
namespace {

namespace fs = std::filesystem;
constexpr double kG = 9.81;

node::NodeOptions pausedNode() {
  node::NodeOptions options;
  options.serve_ipc = false;
  options.real_time_factor = 0.0;
  options.start_paused = true;
  return options;
}

template <class Msg>
class Latest {
 public:
  Latest(realtime::TopicBus& bus, const std::string& topic)
      : bus_(bus), subscription_(bus.subscribe<Msg>(topic, [this](const Msg& msg) {
          std::lock_guard lock(mutex_);
          latest_ = msg;
          ++count_;
        })) {}
  Msg get() {
    bus_.flush();
    std::lock_guard lock(mutex_);
    return latest_;
  }
  int count() {
    bus_.flush();
    std::lock_guard lock(mutex_);
    return count_;
  }

 private:
  realtime::TopicBus& bus_;
  std::mutex mutex_;
  Msg latest_;
  int count_ = 0;
  realtime::Subscription subscription_;
};

class SensorNode : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
#ifndef SERVOLOOP_TEST_MUJOCO
    if (GetParam() == "mujoco") GTEST_SKIP() << "built without MuJoCo (libmujoco-dev)";
#endif
  }
};

TEST_P(SensorNode, SeedRobotPublishesItsImuAndJointWrench) {
  node::LaunchFile launch = node::loadLaunchFile(fs::path(SERVOLOOP_SOURCE_DIR) / "robots" / "one_dof" /
                                                 "one_dof_sensors.launch.yaml");
  launch.world.backend = GetParam();
  node::Node world(launch, pausedNode());
  world.start();
  node::RobotInstance& robot = *world.findRobot("/one_DOF_robot");
  Latest<sensor_msgs::Imu> imu(robot.topics(), "/one_DOF_robot/imu");
  Latest<geometry_msgs::WrenchStamped> ft(robot.topics(), "/one_DOF_robot/joint1_ft");
  realtime::TopicBus& bus = robot.topics();
  std_msgs::Float64 command;
  command.data = 1.0;
  bus.publish("/one_DOF_robot/joint1_position_controller/command", command);
  ASSERT_EQ(world.stepWorld(20000), 20000u);  // the seed's PID settles at 1 rad in about 20 s
  double angle = NAN;
  double rate = NAN;
  for (const node::JointReading& joint : robot.joints()) {
    if (joint.name != "joint1") continue;
    angle = joint.position;
    rate = joint.velocity;
  }
  ASSERT_NEAR(angle, 1.0, 0.01) << "the seed's PID holds the arm at its command";
  ASSERT_LT(std::abs(rate), 0.01) << "nearly at rest";
  EXPECT_GT(imu.count(), 900) << "50 Hz for 20 s";
  EXPECT_GT(ft.count(), 900);

  // The link turned by `angle` about y; the IMU's sensor frame is the link's.
  const Eigen::Matrix3d world_from_link = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const sensor_msgs::Imu reading = imu.get();
  EXPECT_EQ(reading.frame_id, "link2");
  const Eigen::Quaterniond q(reading.orientation.w, reading.orientation.x, reading.orientation.y,
                             reading.orientation.z);
  EXPECT_LT(Eigen::AngleAxisd(q.toRotationMatrix().transpose() * world_from_link).angle(), 1e-3);
  const Eigen::Vector3d up = world_from_link.transpose() * Eigen::Vector3d(0, 0, kG);
  const Eigen::Vector3d accel(reading.linear_acceleration.x, reading.linear_acceleration.y,
                              reading.linear_acceleration.z);
  EXPECT_LT((accel - up).norm(), 0.02) << accel.transpose() << " vs " << up.transpose();

  // The link's weight (1 kg) and its moment about the joint, as the link
  // applies them to the base, in the link's axes.
  const geometry_msgs::WrenchStamped wrench = ft.get();
  EXPECT_EQ(wrench.frame_id, "link2");
  const Eigen::Vector3d weight(0, 0, -kG);
  const Eigen::Vector3d com = world_from_link * Eigen::Vector3d(0, 0, 0.5);
  const Eigen::Vector3d force(wrench.wrench.force.x, wrench.wrench.force.y, wrench.wrench.force.z);
  const Eigen::Vector3d torque(wrench.wrench.torque.x, wrench.wrench.torque.y, wrench.wrench.torque.z);
  EXPECT_LT((force - world_from_link.transpose() * weight).norm(), 0.02) << force.transpose();
  EXPECT_LT((torque - world_from_link.transpose() * com.cross(weight)).norm(), 0.02) << torque.transpose();
}

void writeFile(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

TEST_P(SensorNode, BumperOfAPlateFeelsTheBoxOnIt) {
  servoloop::testing::TempDir dir("servoloop-bumper-" + GetParam());
  writeFile(dir.path() / "plate.urdf", R"(<robot name="plate">
  <link name="world"/>
  <joint name="mount" type="fixed"><parent link="world"/><child link="plate"/><origin xyz="0 0 0.05"/></joint>
  <link name="plate">
    <inertial><mass value="2"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.6 0.6 0.1"/></geometry></collision>
  </link>
  <gazebo reference="plate">
    <sensor name="plate_contact" type="contact">
      <update_rate>100</update_rate>
      <contact><collision>plate_collision</collision></contact>
      <plugin name="plate_bumper" filename="libgazebo_ros_bumper.so">
        <bumperTopicName>plate_bumper</bumperTopicName>
        <frameName>world</frameName>
      </plugin>
    </sensor>
  </gazebo>
</robot>)");
  writeFile(dir.path() / "box.urdf", R"(<robot name="box">
  <link name="box">
    <inertial><mass value="0.8"/><inertia ixx="0.002" iyy="0.002" izz="0.002" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
</robot>)");
  writeFile(dir.path() / "world.launch.yaml", "world: {backend: " + GetParam() +
                                                  ", time_step: 0.001, ground_plane: true}\n"
                                                  "controller_manager: {update_rate: 1000}\n"
                                                  "robots:\n"
                                                  "  - {urdf: plate.urdf, namespace: /plate}\n"
                                                  "  - {urdf: box.urdf, namespace: /box, pose: [0, 0, 0.1505, 0, 0, 0]}\n");
  node::Node world(node::loadLaunchFile(dir.path() / "world.launch.yaml"), pausedNode());
  world.start();
  Latest<gazebo_msgs::ContactsState> bumper(world.findRobot("/plate")->topics(), "/plate/plate_bumper");
  ASSERT_EQ(world.stepWorld(1000), 1000u);  // the box settles on the plate
  EXPECT_GE(bumper.count(), 99) << "100 Hz for 1 s";
  const gazebo_msgs::ContactsState msg = bumper.get();
  EXPECT_EQ(msg.frame_id, "world");
  EXPECT_NEAR(msg.stamp, 1.0, 0.011);
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  bool box_found = false;
  for (const gazebo_msgs::ContactState& state : msg.states) {
    EXPECT_EQ(state.collision1_name, "plate::plate::plate_collision");
    EXPECT_EQ(state.wrenches.size(), state.contact_positions.size());
    EXPECT_EQ(state.depths.size(), state.contact_normals.size());
    if (state.collision2_name != "box::box::box_collision") continue;
    box_found = true;
    total += Eigen::Vector3d(state.total_wrench.force.x, state.total_wrench.force.y, state.total_wrench.force.z);
    for (const geometry_msgs::Vector3& normal : state.contact_normals) {
      EXPECT_NEAR(normal.z, -1.0, 1e-6) << "the box pushes the plate down";
    }
    for (const geometry_msgs::Vector3& position : state.contact_positions) {
      EXPECT_NEAR(position.z, 0.1, 2e-3) << "on the plate's top";
      EXPECT_LE(std::abs(position.x), 0.05 + 1e-3);
    }
  }
  ASSERT_TRUE(box_found) << msg.states.size() << " state(s)";
  EXPECT_LT((total - Eigen::Vector3d(0, 0, -0.8 * kG)).norm(), 0.01 * 0.8 * kG) << total.transpose();
}

struct Circle {
  Eigen::Vector3d angular_velocity;   // the IMU's, mean over the last second
  Eigen::Vector3d specific_force;     // the IMU's, mean over the last second
  double speed = 0.0;                 // ground truth: forward speed and yaw rate at the end
  double yaw_rate = 0.0;
};

Circle driveCircle(const std::string& backend) {
  const fs::path diff_bot = fs::path(SERVOLOOP_SOURCE_DIR) / "robots" / "diff_bot";
  servoloop::testing::TempDir dir("servoloop-imu-circle-" + backend);
  std::ifstream in(diff_bot / "diff_bot.urdf");
  std::string urdf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  urdf.insert(urdf.rfind("</robot>"), R"(<gazebo><plugin name="imu_controller" filename="libhector_gazebo_ros_imu.so">
    <updateRate>100.0</updateRate><bodyName>base_link</bodyName><topicName>imu/data</topicName>
    <accelGaussianNoise>0 0 0</accelGaussianNoise><rateGaussianNoise>0 0 0</rateGaussianNoise>
  </plugin></gazebo>
)");
  writeFile(dir.path() / "diff_bot.urdf", urdf);
  writeFile(dir.path() / "imu.yaml",
            "diff_bot:\n  imu_sensor_controller: {type: imu_sensor_controller/ImuSensorController, publish_rate: 100}\n");
  writeFile(dir.path() / "world.launch.yaml",
            "world: {backend: " + backend + ", time_step: 0.001, ground_plane: true}\n"
            "controller_manager: {update_rate: 1000}\n"
            "robots:\n"
            "  - {urdf: diff_bot.urdf, model: diff_bot, namespace: /diff_bot, pose: [0, 0, 0.1, 0, 0, 0],\n"
            "     params: [" + (diff_bot / "control_config/diff_bot_controllers.yaml").string() + ", imu.yaml],\n"
            "     controllers: [joint_state_controller, diff_drive_controller, imu_sensor_controller]}\n");
  node::Node world(node::loadLaunchFile(dir.path() / "world.launch.yaml"), pausedNode());
  world.start();
  node::RobotInstance& robot = *world.findRobot("/diff_bot");
  realtime::TopicBus& bus = robot.topics();
  std::mutex mutex;
  std::vector<sensor_msgs::Imu> readings;
  const realtime::Subscription subscription =
      bus.subscribe<sensor_msgs::Imu>("/diff_bot/imu/data", [&](const sensor_msgs::Imu& msg) {
        std::lock_guard lock(mutex);
        if (msg.stamp > 5.0) readings.push_back(msg);
      });
  Latest<nav_msgs::Odometry> truth(bus, "/diff_bot/ground_truth/odom");
  geometry_msgs::Twist command;
  command.linear.x = 0.4;
  command.angular.z = 0.5;
  for (int k = 0; k < 60; ++k) {  // 6 s, the command renewed every 0.1 s
    bus.publish("/diff_bot/diff_drive_controller/cmd_vel", command);
    EXPECT_EQ(world.stepWorld(100), 100u);
  }
  bus.flush();
  Circle circle;
  const nav_msgs::Odometry odom = truth.get();
  circle.speed = odom.linear.x;
  circle.yaw_rate = odom.angular.z;
  std::lock_guard lock(mutex);
  EXPECT_GE(readings.size(), 95u) << "100 Hz over the last second";
  circle.angular_velocity.setZero();
  circle.specific_force.setZero();
  for (const sensor_msgs::Imu& msg : readings) {
    circle.angular_velocity += Eigen::Vector3d(msg.angular_velocity.x, msg.angular_velocity.y, msg.angular_velocity.z);
    circle.specific_force +=
        Eigen::Vector3d(msg.linear_acceleration.x, msg.linear_acceleration.y, msg.linear_acceleration.z);
  }
  circle.angular_velocity /= static_cast<double>(std::max<std::size_t>(1, readings.size()));
  circle.specific_force /= static_cast<double>(std::max<std::size_t>(1, readings.size()));
  return circle;
}

// Steady turning: yaw rate ω about z, and the base's origin accelerating
// towards the centre, v·ω to its left (+y); gravity +g up.
TEST_P(SensorNode, ImuOfADrivingBaseReadsItsTurn) {
  const Circle circle = driveCircle(GetParam());
  EXPECT_NEAR(circle.speed, 0.4, 0.02);
  EXPECT_NEAR(circle.yaw_rate, 0.5, 0.02);
  EXPECT_NEAR(circle.angular_velocity.z(), circle.yaw_rate, 0.01);
  EXPECT_NEAR(circle.specific_force.y(), circle.speed * circle.yaw_rate, 0.03) << circle.specific_force.transpose();
  EXPECT_NEAR(circle.specific_force.x(), 0.0, 0.03) << "steady speed";
  EXPECT_NEAR(circle.specific_force.z(), kG, 0.05);
}

TEST(SensorNodeEngines, BulletAndMujocoAgreeOnTheTurningBasesImu) {
#ifndef SERVOLOOP_TEST_MUJOCO
  GTEST_SKIP() << "built without MuJoCo (libmujoco-dev)";
#endif
  const Circle bullet = driveCircle("bullet");
  const Circle mujoco = driveCircle("mujoco");
  EXPECT_LT((bullet.angular_velocity - mujoco.angular_velocity).norm(), 0.02);
  EXPECT_LT((bullet.specific_force - mujoco.specific_force).norm(), 0.05)
      << bullet.specific_force.transpose() << " vs " << mujoco.specific_force.transpose();
}

INSTANTIATE_TEST_SUITE_P(Engines, SensorNode, ::testing::Values("bullet", "mujoco"));

}  // namespace
}  // namespace servoloop::sensor_test
