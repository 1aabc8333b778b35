// Zero allocations on the control thread: 100,000 updates of a
// JointStateController publishing at 50 Hz and the seed's
// effort_controllers/JointPositionController (state topic every 10th update)
// receiving a new setpoint and new PID gains from another thread every 100
// cycles, with the bus's delivery thread running. Also the raw PD and a group controller, and
// a 6-joint trajectory controller taking trajectories, goals, cancels and
// stops while it publishes its state. The IMU and force-torque sensor
// controllers publishing at 500 Hz.
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "alloc_counter.hpp"
#include "controller_test_support.hpp"
#include "servoloop/controllers/effort_controllers/forward_controllers.hpp"
#include "servoloop/controllers/effort_controllers/joint_position_controller.hpp"
#include "servoloop/controllers/joint_state_controller/joint_state_controller.hpp"
#include "servoloop/controllers/diff_drive_controller/diff_drive_controller.hpp"
#include "servoloop/controllers/force_torque_sensor_controller/force_torque_sensor_controller.hpp"
#include "servoloop/controllers/imu_sensor_controller/imu_sensor_controller.hpp"
#include "servoloop/controllers/gripper_action_controller/gripper_action_controller.hpp"
#include "servoloop/controllers/joint_trajectory_controller/joint_trajectory_controller.hpp"
#include "servoloop/realtime/action_registry.hpp"
#include "servoloop/controllers/minimal_joint_controller/minimal_joint_controller.hpp"
#include "servoloop/params/parameters_yaml.hpp"

namespace servoloop::controllers {
namespace {

using testing::initController;
using testing::makeContext;
using testing::TestJointsHW;
using Float64 = servoloop::std_msgs::Float64;
using Float64MultiArray = servoloop::std_msgs::Float64MultiArray;

constexpr int kCycles = 100000;
constexpr int kCommandEvery = 100;

// A callback on every topic the controllers advertised (call after their
// init), so that every real-time publication is queued and delivered.
std::vector<servoloop::realtime::Subscription> listenToEveryTopic(servoloop::realtime::TopicBus& bus) {
  std::vector<servoloop::realtime::Subscription> subscriptions;
  for (const auto& topic : bus.list()) {
    subscriptions.push_back(bus.subscribeAny(topic.name, [](servoloop::Time, const servoloop::realtime::MessageView&) {}));
  }
  return subscriptions;
}

// Escapes the test so the compiler cannot elide the allocation below.
std::unique_ptr<double> g_escaped;

// The counter this test relies on does see an allocation on its thread.
TEST(ControllersAllocation, CounterSeesAnAllocation) {
  servoloop::testing::AllocationCounter counter;
  g_escaped = std::make_unique<double>(1.0);
  EXPECT_GT(counter.allocations(), 0u);
}

TEST(ControllersAllocation, NoAllocationOnTheControlThreadAfterStartUp) {
  servoloop::realtime::TopicBus bus;
  TestJointsHW hw({"joint1", "joint2", "joint3", "joint4"});

  JointStateController joint_states;
  effort_controllers::JointPositionController position;
  MinimalJointController raw_pd;
  effort_controllers::JointGroupEffortController group;
  initController(joint_states, hw,
                 makeContext("joint_state_controller", "{publish_rate: 50, extra_joints: [{name: x}]}", &bus));
  controller_manager::ControllerContext position_context;
  position_context.name = "joint1_position_controller";
  position_context.robot_namespace = "/one_DOF_robot";
  position_context.params = servoloop::params::parametersFromYaml(
      testing::seedControllerParams()["joint1_position_controller"], "/one_DOF_robot/joint1_position_controller");
  position_context.topics = &bus;
  position_context.robot_model = testing::seedRobotModel();
  initController(position, hw, position_context);
  initController(raw_pd, hw, makeContext("pd", "{joint: joint2}", &bus));
  // Commands come every 0.1 s and time out after 0.05 s: a timeout (and its
  // publication) in every interval.
  initController(group, hw, makeContext("group", "{joints: [joint3, joint4], command_timeout: 0.05}", &bus));

  std::uint64_t joint_state_messages = 0;
  auto subscription = bus.subscribe<servoloop::sensor_msgs::JointState>(
      "/robot/joint_states", [&](const auto&) { ++joint_state_messages; });
  // Every topic listened to, so every publication is copied into its queue
  // (a topic nobody listens to costs its publisher no copy).
  const auto listeners = listenToEveryTopic(bus);
  bus.start();

  // The control thread asks for a command every kCommandEvery cycles and
  // waits until this thread has published it, so every command is seen.
  std::atomic<int> requested{0};
  std::atomic<int> published{0};
  std::size_t allocations = 0;
  double final_setpoint = 0.0;
  std::thread control([&] {
    const Duration period(0.001);
    joint_states.startRequest(Time(0.0));
    position.startRequest(Time(0.0));
    raw_pd.startRequest(Time(0.0));
    group.startRequest(Time(0.0));
    servoloop::testing::AllocationCounter counter;  // this thread only, from here on
    for (int k = 1; k <= kCycles; ++k) {
      if (k % kCommandEvery == 0) {
        requested.store(k / kCommandEvery);
        while (published.load() != k / kCommandEvery) std::this_thread::yield();
      }
      const Time now(0.001 * k);
      hw.position[0] = 1.0 + 0.5 * std::sin(0.001 * k);
      joint_states.update(now, period);
      position.update(now, period);
      raw_pd.update(now, period);
      group.update(now, period);
    }
    allocations = counter.allocations();
    final_setpoint = position.setpoint();
  });
  for (int n = 1; n <= kCycles / kCommandEvery; ++n) {
    while (requested.load() != n) std::this_thread::yield();
    const double setpoint = 0.25 + 1.5 * static_cast<double>(n % 7) / 6.0;  // inside [0, 2]
    bus.publish("/one_DOF_robot/joint1_position_controller/command", Float64{setpoint});
    bus.publish("/robot/pd/pos_cmd", Float64{-setpoint});
    bus.publish("/robot/group/command", Float64MultiArray{{setpoint, -setpoint}});
    // New gains, as `control gains` or dynamic_reconfigure set them.
    position.pid().setGains(10.0 + n % 5, 10.0, 10.0 + n % 3, 10.0, -10.0, n % 2 == 0);
    published.store(n);
  }
  control.join();
  bus.stop();

  EXPECT_EQ(allocations, 0u);
  const int last = kCycles / kCommandEvery;
  // The last gains were taken at the update after they were set.
  const Pid::Gains active = position.pid().getActiveGains();
  EXPECT_EQ(active.p_gain, 10.0 + last % 5);
  EXPECT_EQ(active.d_gain, 10.0 + last % 3);
  EXPECT_EQ(active.antiwindup, last % 2 == 0);
  EXPECT_DOUBLE_EQ(final_setpoint, 0.25 + 1.5 * static_cast<double>(last % 7) / 6.0);
  EXPECT_DOUBLE_EQ(hw.effort_command[2], final_setpoint);  // the group's last command
  // One timeout before the first command (t = 0.05 s), then one 0.05 s after
  // each command but the last (which came in the final cycle).
  EXPECT_EQ(group.commandTimeouts(), static_cast<std::uint64_t>(kCycles / kCommandEvery));
  // 50 Hz over 100 s of control time: the first cycle, then every 20th.
  EXPECT_EQ(joint_states.publishedCount(), static_cast<std::uint64_t>(kCycles / 20));
  EXPECT_GT(joint_state_messages, 0u);
}

// Every 100 cycles the trajectory controller gets, in turn: a trajectory on
// its topic (cubic points), a goal (quintic points) that succeeds or is
// preempted, a goal with a path tolerance the still joints violate (aborted,
// then the stop profile), a cancel of a goal, and an empty trajectory (stop).
TEST(ControllersAllocation, TrajectoryControllerTakesTrajectoriesAndGoalsWithoutAllocating) {
  namespace jtc = joint_trajectory_controller;
  servoloop::realtime::TopicBus bus;
  const std::vector<std::string> joints = {"j1", "j2", "j3", "j4", "j5", "j6"};
  TestJointsHW hw(joints);
  jtc::EffortJointTrajectoryController controller;
  std::string gains;
  for (const auto& joint : joints) gains += (gains.empty() ? "" : ", ") + joint + ": {p: 100, d: 5, i: 1, i_clamp: 1}";
  initController(controller, hw,
                 makeContext("arm",
                             "{joints: [j1, j2, j3, j4, j5, j6], gains: {" + gains +
                                 "}, stop_trajectory_duration: 0.05, state_publish_rate: 100}",
                             &bus));
  std::uint64_t states = 0;
  auto subscription = bus.subscribe<servoloop::control_msgs::JointTrajectoryControllerState>(
      "/robot/arm/state", [&](const auto&) { ++states; });
  bus.start();

  const auto trajectory = [&](double scale, bool with_accelerations) {
    servoloop::trajectory_msgs::JointTrajectory msg;
    msg.joint_names = joints;
    for (int i = 1; i <= 4; ++i) {
      servoloop::trajectory_msgs::JointTrajectoryPoint point;
      point.positions.assign(6, scale * i);
      point.velocities.assign(6, i < 4 ? 0.1 * i : 0.0);  // at rest at the end
      if (with_accelerations) point.accelerations.assign(6, 0.0);
      point.time_from_start = 0.02 * i;
      msg.points.push_back(point);
    }
    return msg;
  };

  std::atomic<int> requested{0};
  std::atomic<int> published{0};
  std::size_t allocations = 0;
  std::thread control([&] {
    const Duration period(0.001);
    controller.startRequest(Time(0.0));
    servoloop::testing::AllocationCounter counter;
    for (int k = 1; k <= kCycles; ++k) {
      if (k % kCommandEvery == 0) {
        requested.store(k / kCommandEvery);
        while (published.load() != k / kCommandEvery) std::this_thread::yield();
      }
      const Time now(0.001 * k);
      bus.setTime(now);
      for (std::size_t j = 0; j < 6; ++j) hw.position[j] = 0.01 * std::sin(0.001 * k + static_cast<double>(j));
      controller.update(now, period);
    }
    allocations = counter.allocations();
  });
  int goals = 0, topic_trajectories = 0;
  std::vector<std::shared_ptr<jtc::TrajectoryGoal>> kept;
  for (int n = 1; n <= kCycles / kCommandEvery; ++n) {
    while (requested.load() != n) std::this_thread::yield();
    jtc::TrajectoryTolerances tolerances = controller.follower().defaultTolerances();
    switch (n % 5) {
      case 0:
        bus.publish("/robot/arm/command", trajectory(0.1, false));
        bus.flush();
        ++topic_trajectories;
        break;
      case 1:
        kept.push_back(controller.follower().submitGoal(trajectory(-0.1, true), tolerances));
        ++goals;
        break;
      case 2:
        for (auto& t : tolerances.path) t.position = 0.01;
        kept.push_back(controller.follower().submitGoal(trajectory(0.2, false), tolerances));
        ++goals;
        break;
      case 3:
        kept.back()->requestCancel();
        break;
      case 4:
        bus.publish("/robot/arm/command", servoloop::trajectory_msgs::JointTrajectory{0.0, joints, {}});
        bus.flush();
        break;
    }
    published.store(n);
  }
  control.join();
  bus.stop();

  EXPECT_EQ(allocations, 0u);
  EXPECT_EQ(controller.follower().trajectoriesTaken(), static_cast<std::uint64_t>(goals + topic_trajectories));
  EXPECT_EQ(controller.follower().trajectoriesRefused(), 0u);
  int aborted = 0;
  for (const auto& goal : kept) {
    EXPECT_TRUE(goal->done());
    aborted += goal->status() == jtc::GoalStatus::aborted;
  }
  EXPECT_EQ(aborted, goals / 2);  // every path-tolerance goal, no other
  EXPECT_GT(states, static_cast<std::uint64_t>(kCycles / 10 / 2));
}

// The effort gripper controller through its action: a goal every 100
// cycles (from another thread, through the action registry), every third one
// canceled, feedback read while it runs.
TEST(ControllersAllocation, GripperControllerTakesGoalsWithoutAllocating) {
  namespace gac = gripper_action_controller;
  servoloop::realtime::TopicBus bus;
  servoloop::realtime::ActionRegistry actions;
  TestJointsHW hw({"finger"});
  gac::EffortGripperActionController gripper;
  auto context = makeContext("gripper", "{joint: finger, gains: {finger: {p: 100, d: 5}}, stall_timeout: 0.02}", &bus);
  context.actions = &actions;
  initController(gripper, hw, context);

  std::atomic<int> requested{0};
  std::atomic<int> published{0};
  std::size_t allocations = 0;
  std::thread control([&] {
    const Duration period(0.001);
    gripper.startRequest(Time(0.0));
    servoloop::testing::AllocationCounter counter;
    for (int k = 1; k <= kCycles; ++k) {
      if (k % kCommandEvery == 0) {
        requested.store(k / kCommandEvery);
        while (published.load() != k / kCommandEvery) std::this_thread::yield();
      }
      hw.position[0] = 0.001 * std::sin(0.01 * k);
      gripper.update(Time(0.001 * k), period);
    }
    allocations = counter.allocations();
  });
  std::vector<std::shared_ptr<servoloop::realtime::ActionGoal>> goals;
  servoloop::control_msgs::GripperCommandFeedback feedback;
  for (int n = 1; n <= kCycles / kCommandEvery; ++n) {
    while (requested.load() != n) std::this_thread::yield();
    const servoloop::control_msgs::GripperCommandGoal goal{{0.01 * (n % 3), 2.0}};
    goals.push_back(actions.sendGoal("/robot/gripper/gripper_cmd", goal.kActionType, &goal));
    if (n % 3 == 0) goals.back()->cancel();
    if (n > 1) goals[goals.size() - 2]->feedback(&feedback);
    published.store(n);
  }
  control.join();
  EXPECT_EQ(allocations, 0u);
  for (std::size_t i = 0; i + 1 < goals.size(); ++i) EXPECT_TRUE(servoloop::realtime::goalDone(goals[i]->state()));
}

// The diff drive controller with its limits on, publishing odom and tf at
// 50 Hz with the delivery thread running, taking a cmd_vel every 100 cycles
// (and timing out between them).
TEST(ControllersAllocation, DiffDriveControllerWithoutAllocating) {
  servoloop::realtime::TopicBus bus;
  TestJointsHW hw({"left_wheel", "right_wheel"});
  diff_drive_controller::DiffDriveController base;
  initController(base, hw,
                 makeContext("base",
                             "{left_wheel: left_wheel, right_wheel: right_wheel, wheel_separation: 0.4, "
                             "wheel_radius: 0.05, cmd_vel_timeout: 0.05, "
                             "linear: {x: {has_velocity_limits: true, max_velocity: 1.0, "
                             "has_acceleration_limits: true, max_acceleration: 2.0, has_jerk_limits: true, max_jerk: 50}}, "
                             "angular: {z: {has_velocity_limits: true, max_velocity: 2.0}}}",
                             &bus));
  std::uint64_t odom_messages = 0;
  auto subscription = bus.subscribe<servoloop::nav_msgs::Odometry>(
      "/robot/base/odom", [&](const auto&) { ++odom_messages; });
  const auto listeners = listenToEveryTopic(bus);  // /tf too
  bus.start();
  std::atomic<int> requested{0};
  std::atomic<int> published{0};
  std::size_t allocations = 0;
  std::thread control([&] {
    const Duration period(0.001);
    base.startRequest(Time(0.0));
    servoloop::testing::AllocationCounter counter;
    for (int k = 1; k <= kCycles; ++k) {
      if (k % kCommandEvery == 0) {
        requested.store(k / kCommandEvery);
        while (published.load() != k / kCommandEvery) std::this_thread::yield();
      }
      const Time now(0.001 * k);
      bus.setTime(now);
      base.update(now, period);
      for (std::size_t i = 0; i < 2; ++i) hw.position[i] += 0.001 * hw.velocity_command[i];
    }
    allocations = counter.allocations();
  });
  for (int n = 1; n <= kCycles / kCommandEvery; ++n) {
    while (requested.load() != n) std::this_thread::yield();
    servoloop::geometry_msgs::Twist twist;
    twist.linear.x = 0.5 * std::sin(0.1 * n);
    twist.angular.z = std::cos(0.1 * n);
    bus.publish("/robot/base/cmd_vel", twist);
    published.store(n);
  }
  control.join();
  bus.stop();
  EXPECT_EQ(allocations, 0u);
  EXPECT_GT(odom_messages, 0u);
  EXPECT_TRUE(std::isfinite(base.odometry().x()));
}

// The sensor controllers publishing every other cycle (500 Hz in a 1 kHz
// loop), frames longer than a short string, with the delivery thread running
// and every topic listened to, while the readings change every cycle.
TEST(ControllersAllocation, SensorControllersPublishWithoutAllocating) {
  servoloop::realtime::TopicBus bus;
  testing::TestSensorsHW hw;
  testing::TestSensorsHW::ImuStorage& imu = hw.addImu("imu", "an_imu_frame_longer_than_sso");
  const double gyro_rate[3] = {0.0, 0.0, 0.5};
  hardware_interface::ImuSensorHandle::Data gyro;
  gyro.name = "gyro";
  gyro.frame_id = "gyro_link";
  gyro.angular_velocity = gyro_rate;
  hw.addImu(gyro);
  testing::TestSensorsHW::ForceTorqueStorage& wrist = hw.addForceTorque("wrist_ft", "a_force_torque_frame_this_long");
  hw.addForceTorque("ankle_ft", "foot");
  ImuSensorController imus;
  ForceTorqueSensorController force_torques;
  initController(imus, hw, makeContext("imu_sensor_controller", "{publish_rate: 500}", &bus));
  initController(force_torques, hw, makeContext("ft_sensor_controller", "{publish_rate: 500}", &bus));
  std::uint64_t imu_messages = 0;
  auto subscription = bus.subscribe<servoloop::sensor_msgs::Imu>("/robot/imu", [&](const auto& msg) {
    if (msg.frame_id == "an_imu_frame_longer_than_sso") ++imu_messages;
  });
  const auto listeners = listenToEveryTopic(bus);
  bus.start();
  std::size_t allocations = 0;
  std::thread control([&] {
    const Duration period(0.001);
    imus.startRequest(Time(0.0));
    force_torques.startRequest(Time(0.0));
    servoloop::testing::AllocationCounter counter;
    for (int k = 1; k <= kCycles; ++k) {
      const Time now(0.001 * k);
      bus.setTime(now);
      imu.angular_velocity[2] = std::sin(0.001 * k);
      wrist.force[2] = 10.0 * std::cos(0.001 * k);
      imus.update(now, period);
      force_torques.update(now, period);
    }
    allocations = counter.allocations();
  });
  control.join();
  bus.stop();
  EXPECT_EQ(allocations, 0u);
  // Two sensors each, every other cycle: kCycles messages each, less the few
  // a real-time publisher skips when the delivery thread holds its message
  // at that moment (as ros_control's RealtimePublisher does; more of them on
  // a slow machine or under a sanitizer).
  for (const std::uint64_t published : {imus.publishedCount(), force_torques.publishedCount()}) {
    EXPECT_LE(published, static_cast<std::uint64_t>(kCycles));
    EXPECT_GT(published, static_cast<std::uint64_t>(kCycles) * 9 / 10);
  }
  EXPECT_GT(imu_messages, 0u);
}

}  // namespace
}  // namespace servoloop::controllers
