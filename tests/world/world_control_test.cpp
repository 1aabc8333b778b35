// World control on a running node (Node::pauseWorld, stepWorld, resetWorld,
// as `servoloop world pause|step|reset` reach them): a paused world stands,
// steps run exactly the steps asked for, and a reset world runs the same
// inputs bit-identically to a fresh launch, on bullet (robots and objects in
// contact) and on mujoco.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <tuple>
#include <string>
#include <vector>

#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/simulated_robot_hw.hpp"
#include "servoloop/node/node.hpp"
#include "temp_dir.hpp"
#include "world_test_support.hpp"

namespace servoloop::world_test {
namespace {

using node::LaunchFile;
using node::Node;
using node::NodeOptions;
using servoloop::testing::TempDir;
using servoloop::testing::writeFile;

// Every robot's joints and base ground truth, exact while the world is paused.
std::vector<double> snapshot(Node& node) {
  std::vector<double> values;
  for (node::RobotInstance* robot : node.robots()) {
    for (const node::JointReading& joint : robot->joints()) {
      values.insert(values.end(), {joint.position, joint.velocity, joint.effort});
    }
    auto* simulated = dynamic_cast<hardware_interface::SimulatedRobotHW*>(&robot->hardware());
    hardware_interface::BaseGroundTruth base;
    if (simulated != nullptr && simulated->readBaseGroundTruth(base)) {
      values.insert(values.end(), std::begin(base.position), std::end(base.position));
      values.insert(values.end(), std::begin(base.orientation), std::end(base.orientation));
      values.insert(values.end(), std::begin(base.linear_velocity), std::end(base.linear_velocity));
      values.insert(values.end(), std::begin(base.angular_velocity), std::end(base.angular_velocity));
    }
  }
  return values;
}

// `chunks` × `steps` physics steps, a snapshot after each chunk.
std::vector<std::vector<double>> trajectory(Node& node, int chunks, std::uint64_t steps) {
  std::vector<std::vector<double>> states;
  for (int i = 0; i < chunks; ++i) {
    EXPECT_EQ(node.stepWorld(steps), steps);
    states.push_back(snapshot(node));
  }
  return states;
}

// Bitwise: -0.0 and 0.0 differ, NaN equals the same NaN.
bool bitIdentical(const std::vector<std::vector<double>>& a, const std::vector<std::vector<double>>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].size() != b[i].size()) return false;
    if (std::memcmp(a[i].data(), b[i].data(), a[i].size() * sizeof(double)) != 0) return false;
  }
  return true;
}

// The base drives into the box from t = 0.5 s: contacts between robots and
// with the ground in every step.
TEST(WorldControl, AResetBulletWorldOfRobotsInContactRunsBitIdenticallyToAFreshLaunch) {
  TempDir dir("servoloop-world-reset-bullet");
  const LaunchFile launch = node::loadLaunchFile(writePushWorld(dir.path(), "bullet", 0.4, 3.0, 0.6));

  Node fresh(launch, pausedOptions());
  fresh.start();
  const std::vector<double> at_start = snapshot(fresh);
  const auto first = trajectory(fresh, 30, 100);  // 3 s
  // The box was pushed: contact, not a trajectory of a robot alone.
  node::RobotInstance* box = fresh.findRobot("/box");
  ASSERT_NE(box, nullptr);
  hardware_interface::BaseGroundTruth box_pose;
  ASSERT_TRUE(dynamic_cast<hardware_interface::SimulatedRobotHW&>(box->hardware()).readBaseGroundTruth(box_pose));
  EXPECT_GT(box_pose.position[0], 0.6 + 0.2) << "the base did not push the box";

  EXPECT_EQ(fresh.resetWorld(), "");
  EXPECT_TRUE(fresh.worldState().paused) << "a paused world stays paused through a reset";
  EXPECT_EQ(fresh.worldState().steps, 0u);
  EXPECT_DOUBLE_EQ(fresh.simTime(), 0.0);
  EXPECT_TRUE(bitIdentical({snapshot(fresh)}, {at_start})) << "every body back at its start pose, at rest";
  const auto after_reset = trajectory(fresh, 30, 100);
  EXPECT_TRUE(bitIdentical(first, after_reset)) << "the reset world ran differently from its first run";

  // And a second reset, after a different history (stepped in other chunks).
  (void)trajectory(fresh, 7, 33);
  EXPECT_EQ(fresh.resetWorld(), "");
  EXPECT_TRUE(bitIdentical(first, trajectory(fresh, 30, 100)));
  fresh.shutdown();

  Node another(launch, pausedOptions());
  another.start();
  EXPECT_TRUE(bitIdentical(first, trajectory(another, 30, 100))) << "two fresh launches differ";
}

// The seed robot on mujoco, its position controller (PID with an integral
// term) commanded by a timed publication: the controller's state resets too.
TEST(WorldControl, AResetMujocoWorldRunsBitIdenticallyToAFreshLaunch) {
#ifndef SERVOLOOP_TEST_MUJOCO
  GTEST_SKIP() << "built without MuJoCo (libmujoco-dev)";
#endif
  TempDir dir("servoloop-world-reset-mujoco");
  LaunchFile launch = node::loadLaunchFile(fs::path(SERVOLOOP_SOURCE_DIR) / "robots/one_dof/one_dof_w_jnt_ctl.launch.yaml");
  launch.world.backend = "mujoco";
  node::TimedPublication command;
  command.topic = "/one_DOF_robot/joint1_position_controller/command";
  command.type = "std_msgs/Float64";
  command.message = {{"data", 1.0}};
  command.time_s = 0.2;
  launch.publish.push_back(command);

  Node world(launch, pausedOptions());
  world.start();
  const auto first = trajectory(world, 20, 100);
  ASSERT_GT(first.back().at(0), 0.5) << "the joint did not follow its command";
  EXPECT_EQ(world.resetWorld(), "");
  EXPECT_TRUE(bitIdentical(first, trajectory(world, 20, 100)));
  world.shutdown();

  Node another(launch, pausedOptions());
  another.start();
  EXPECT_TRUE(bitIdentical(first, trajectory(another, 20, 100)));
}

TEST(WorldControl, APausedWorldStandsAndStepsExactlyTheStepsAskedFor) {
  TempDir dir("servoloop-world-pause");
  NodeOptions options = pausedOptions();
  options.start_paused = false;
  Node world(node::loadLaunchFile(writePushWorld(dir.path(), "bullet", 0.4, 1.0, 0.0)), options);
  world.start();
  EXPECT_THROW(world.stepWorld(1), Error) << "a running world is not stepped";
  world.pauseWorld();
  const node::WorldState paused = world.worldState();
  EXPECT_TRUE(paused.paused);
  // Nothing ran between the pause and the steps: exactly 25 more.
  EXPECT_EQ(world.stepWorld(25), 25u);
  const node::WorldState stepped = world.worldState();
  EXPECT_EQ(stepped.steps, paused.steps + 25);
  EXPECT_DOUBLE_EQ(stepped.sim_time_s, static_cast<double>(stepped.steps) * 0.001);
  world.unpauseWorld();
  EXPECT_FALSE(world.worldState().paused);
  world.pauseWorld();
  EXPECT_GE(world.worldState().steps, stepped.steps);
}

// Gazebo's set_model_configuration and get_model_state: joints moved to
// the positions given, at rest; a free box's pose and a fixed arm's.
TEST(WorldControl, SetModelConfigurationMovesJointsAtRestAndModelStateReportsPoses) {
  TempDir dir("servoloop-world-configuration");
  const fs::path push = writePushWorld(dir.path(), "bullet", 0.4, 1.0, 0.6);
  LaunchFile launch = node::loadLaunchFile(push);
  Node world(launch, pausedOptions());
  world.start();
  (void)trajectory(world, 1, 50);
  world.setModelConfiguration("diff_bot", {"left_wheel_joint"}, {0.75});
  const auto joints = world.findRobot("/diff_bot")->joints();
  const auto left = std::find_if(joints.begin(), joints.end(), [](const auto& j) { return j.name == "left_wheel_joint"; });
  ASSERT_NE(left, joints.end());
  EXPECT_EQ(left->position, 0.75);
  EXPECT_EQ(left->velocity, 0.0);
  for (const auto& [model, joint_names, positions, expected] :
       std::vector<std::tuple<std::string, std::vector<std::string>, std::vector<double>, std::string>>{
           {"diff_bot", {"elbow"}, {0.1}, "elbow"},
           {"diff_bot", {"left_wheel_joint"}, {NAN}, "finite"},
           {"diff_bot", {"left_wheel_joint"}, {0.1, 0.2}, "one position per joint"},
           {"nobody", {"left_wheel_joint"}, {0.1}, "/diff_bot"}}) {
    try {
      world.setModelConfiguration(model, joint_names, positions);
      ADD_FAILURE() << "accepted: " << model << " " << expected;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
  const node::ModelState box = world.modelState("box");
  EXPECT_FALSE(box.fixed);
  EXPECT_NEAR(box.position[0], 0.6, 1e-3);
  EXPECT_NEAR(box.position[2], 0.1, 2e-3);  // resting on the ground, 0.2 m high
  EXPECT_NEAR(box.orientation[3], 1.0, 1e-6);
  EXPECT_THROW(world.modelState("nobody"), Error);
}

TEST(WorldControl, AWorldOnTheWallClockRefusesPauseStepAndReset) {
  TempDir dir("servoloop-world-wall");
  LaunchFile launch = node::loadLaunchFile(writePushWorld(dir.path(), "mock", 0.4, 1.0, 0.0));
  launch.world.wall_clock = true;
  NodeOptions options;
  options.serve_ipc = false;
  Node world(launch, options);
  world.start();
  for (const auto& call : std::vector<std::function<void()>>{[&] { world.pauseWorld(); },
                                                             [&] { (void)world.stepWorld(1); },
                                                             [&] { (void)world.resetWorld(); }}) {
    try {
      call();
      ADD_FAILURE() << "a world on the wall clock was controlled";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("wall clock"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace servoloop::world_test
