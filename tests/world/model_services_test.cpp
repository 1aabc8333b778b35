// Gazebo's model services on a running node (Node::setModelState and
// Node::deleteModel, as `servoloop model set|delete` reach them): a box
// thrown with set_model_state flies the ballistic path of the closed-form
// solution on bullet and mujoco, a pose set is the pose read back, bad
// requests change nothing, and a model deleted while the world runs leaves
// the others running, with a trajectory bit-identical to a world that never
// had it (on both engines).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <thread>
#include <cmath>
#include <cstring>
#include <mutex>
#include <optional>
#include <array>
#include <string>
#include <vector>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/hardware_interface/simulated_robot_hw.hpp"
#include "servoloop/node/node.hpp"
#include "servoloop/realtime/messages.hpp"
#include "servoloop/realtime/topic_bus.hpp"
#include "temp_dir.hpp"
#include "world_test_support.hpp"

namespace servoloop::world_test {
namespace {

using node::LaunchFile;
using node::ModelPose;
using node::ModelState;
using node::ModelTwist;
using node::Node;
using node::NodeOptions;
using servoloop::testing::TempDir;
using servoloop::testing::writeFile;

constexpr double kGravity = 9.81;

// A world on `backend` with the ground plane, a 1 ms step and, for each of
// `boxes`, a free 0.2 m, 1 kg box resting at x = 0.6 k (namespaces /box0 ...).
fs::path writeBoxWorld(const fs::path& dir, const std::string& backend, int boxes) {
  writeFile(dir / "box.urdf", boxUrdf(0.2, 1.0, 1.0));
  std::string yaml = "world: {backend: " + backend + ", time_step: 0.001, ground_plane: true}\n"
                     "controller_manager: {update_rate: 1000}\nrobots:\n";
  for (int k = 0; k < boxes; ++k) {
    yaml += "  - {urdf: box.urdf, namespace: /box" + std::to_string(k) + ", pose: [" + std::to_string(0.6 * k) +
            ", 0, 0.1, 0, 0, 0]}\n";
  }
  const fs::path launch = dir / "boxes.launch.yaml";
  writeFile(launch, yaml);
  return launch;
}

ModelPose poseAt(double x, double y, double z, double yaw = 0.0) {
  ModelPose pose;
  pose.position[0] = x;
  pose.position[1] = y;
  pose.position[2] = z;
  pose.orientation[2] = std::sin(yaw / 2);
  pose.orientation[3] = std::cos(yaw / 2);
  return pose;
}

ModelTwist twistOf(double vx, double vy, double vz, double wz) {
  ModelTwist twist;
  twist.linear[0] = vx;
  twist.linear[1] = vy;
  twist.linear[2] = vz;
  twist.angular[2] = wz;
  return twist;
}

std::vector<double> stateValues(const ModelState& state) {
  std::vector<double> values(std::begin(state.position), std::end(state.position));
  values.insert(values.end(), std::begin(state.orientation), std::end(state.orientation));
  values.insert(values.end(), std::begin(state.linear_velocity), std::end(state.linear_velocity));
  values.insert(values.end(), std::begin(state.angular_velocity), std::end(state.angular_velocity));
  return values;
}

// Waits (up to 30 s) until the running world has stepped past `steps`.
bool stepsPass(Node& world, std::uint64_t steps) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (world.worldState().steps <= steps) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::yield();
  }
  return true;
}

class ModelServices : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
#ifndef SERVOLOOP_TEST_MUJOCO
    if (GetParam() == "mujoco") GTEST_SKIP() << "built without MuJoCo (libmujoco-dev)";
#endif
  }
};

// The box of writeBoxWorld welded to the world at (3, 0, 0.5), model "welded".
node::RobotSpec weldedBox(const fs::path& dir) {
  node::RobotSpec fixed;
  fixed.urdf = dir / "box.urdf";
  fixed.model = "welded";
  fixed.robot_namespace = "/welded";
  fixed.fixed_base = true;
  fixed.pose = std::array<double, 6>{3.0, 0.0, 0.5, 0.0, 0.0, 0.0};
  return fixed;
}

// Thrown from 5 m up at (1, 0.5, 3) m/s spinning at 2 rad/s about z: free
// flight, x = x0 + vx t, z = z0 + vz t - g t^2 / 2, vz = vz0 - g t, and a
// cube's spin about its axis of symmetry stays (yaw = 2 t).
TEST_P(ModelServices, AThrownBoxFliesTheBallisticPath) {
  const std::string backend = GetParam();
  TempDir dir("servoloop-model-throw-" + backend);
  Node world(node::loadLaunchFile(writeBoxWorld(dir.path(), backend, 1)), pausedOptions());
  world.start();
  ASSERT_EQ(world.stepWorld(10), 10u);
  world.setModelState("box0", poseAt(0.0, 0.0, 5.0), twistOf(1.0, 0.5, 3.0, 2.0));

  const ModelState set = world.modelState("box0");
  EXPECT_EQ(set.position[2], 5.0) << "the pose set is the pose read back";
  EXPECT_NEAR(set.linear_velocity[2], 3.0, 1e-12);
  EXPECT_NEAR(set.angular_velocity[2], 2.0, 1e-12);

  const double t = 0.5;
  ASSERT_EQ(world.stepWorld(500), 500u);
  const ModelState flown = world.modelState("box0");
  // Semi-implicit Euler with a 1 ms step: the height is off by g t dt / 2
  // (2.5 mm) at most; the velocities are exact to rounding.
  EXPECT_NEAR(flown.position[0], 1.0 * t, 1e-6);
  EXPECT_NEAR(flown.position[1], 0.5 * t, 1e-6);
  EXPECT_NEAR(flown.position[2], 5.0 + 3.0 * t - kGravity * t * t / 2, 3e-3);
  EXPECT_NEAR(flown.linear_velocity[0], 1.0, 1e-6);
  EXPECT_NEAR(flown.linear_velocity[2], 3.0 - kGravity * t, 1e-6);
  EXPECT_NEAR(flown.angular_velocity[2], 2.0, 1e-6);
  const double yaw = 2.0 * std::atan2(flown.orientation[2], flown.orientation[3]);
  EXPECT_NEAR(yaw, 2.0 * t, 1e-3);
}

// A request that cannot be carried out is refused with one error naming the
// value, and nothing in the world moved.
TEST_P(ModelServices, BadRequestsAreRefusedAndMoveNothing) {
  const std::string backend = GetParam();
  TempDir dir("servoloop-model-bad-" + backend);
  Node world(node::loadLaunchFile(writeBoxWorld(dir.path(), backend, 2)), pausedOptions());
  const node::RobotSpec fixed = weldedBox(dir.path());
  world.spawnRobot(fixed);
  world.start();
  ASSERT_EQ(world.stepWorld(20), 20u);
  const std::vector<double> before = stateValues(world.modelState("box0"));

  ModelPose zero_rotation = poseAt(0.0, 0.0, 1.0);
  zero_rotation.orientation[3] = 0.0;
  const ModelPose not_a_number = poseAt(0.0, NAN, 1.0);
  const ModelTwist infinite = twistOf(INFINITY, 0.0, 0.0, 0.0);
  struct Case {
    std::string model;
    std::optional<ModelPose> pose;
    std::optional<ModelTwist> twist;
    std::string expected;
  };
  for (const Case& c : std::vector<Case>{{"box0", zero_rotation, std::nullopt, "quaternion"},
                                         {"box0", not_a_number, std::nullopt, "finite"},
                                         {"box0", std::nullopt, infinite, "finite"},
                                         {"nobody", poseAt(0, 0, 1), std::nullopt, "/box0, /box1, /welded"},
                                         {"welded", poseAt(0, 0, 1), std::nullopt, "fixed base"}}) {
    try {
      world.setModelState(c.model, c.pose, c.twist);
      ADD_FAILURE() << "accepted: " << c.model << " (" << c.expected << ")";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(c.expected), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(stateValues(world.modelState("box0")), before) << "a refused request moved the box";
  try {
    world.deleteModel("nobody");
    ADD_FAILURE() << "deleted a model that is not there";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/box0, /box1, /welded"), std::string::npos) << e.what();
  }
  node::RobotSpec twin = fixed;
  twin.robot_namespace = "/twin";
  try {
    world.spawnRobot(twin);
    ADD_FAILURE() << "a second model named 'welded' was spawned";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a model named 'welded' exists already (namespace /welded)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(world.robotNamespaces().size(), 3u);
}

// /gazebo/model_states at 50 Hz of world time (every 20 steps of 1 ms):
// every model by name (robots of one URDF by namespace), a floating base's
// ground truth as model.get gives it at that step, a fixed base at its
// spawn pose.
TEST_P(ModelServices, ModelStatesListEveryModelAtFiftyHertz) {
  const std::string backend = GetParam();
  TempDir dir("servoloop-model-states-" + backend);
  Node world(node::loadLaunchFile(writeBoxWorld(dir.path(), backend, 2)), pausedOptions());
  const node::RobotSpec fixed = weldedBox(dir.path());
  world.spawnRobot(fixed);
  std::mutex mutex;
  std::vector<gazebo_msgs::ModelStates> received;
  realtime::TopicBus& bus = world.findRobot("/box0")->topics();
  const realtime::Subscription subscription =
      bus.subscribe<gazebo_msgs::ModelStates>("/gazebo/model_states", [&](const gazebo_msgs::ModelStates& msg) {
        std::lock_guard lock(mutex);
        received.push_back(msg);
      });
  world.start();
  world.setModelState("box0", poseAt(0.0, 0.0, 3.0), twistOf(0.5, 0.0, 1.0, 0.0));
  ASSERT_EQ(world.stepWorld(180), 180u);
  const ModelState at_180 = world.modelState("/box0");
  ASSERT_EQ(world.stepWorld(20), 20u);
  bus.flush();
  std::lock_guard lock(mutex);
  // Steps 0, 20, ..., 180: ten messages in the first 200 steps.
  ASSERT_EQ(received.size(), 10u);
  const gazebo_msgs::ModelStates& last = received.back();
  ASSERT_EQ(last.name, (std::vector<std::string>{"box0", "box1", "welded"}));
  ASSERT_EQ(last.pose.size(), 3u);
  ASSERT_EQ(last.twist.size(), 3u);
  EXPECT_EQ(last.pose[0].position.z, at_180.position[2]);
  EXPECT_EQ(last.pose[0].position.x, at_180.position[0]);
  EXPECT_EQ(last.twist[0].linear.z, at_180.linear_velocity[2]);
  EXPECT_LT(last.pose[0].position.z, received.front().pose[0].position.z + 0.2) << "the box did not fly";
  EXPECT_NEAR(last.pose[1].position.x, 0.6, 1e-3);
  EXPECT_NEAR(last.pose[1].position.z, 0.1, 2e-3) << "box1 rests on the ground";
  EXPECT_EQ(last.pose[2].position.x, 3.0);
  EXPECT_EQ(last.pose[2].position.z, 0.5);
  EXPECT_EQ(last.pose[2].orientation.w, 1.0);
  EXPECT_EQ(last.twist[2].linear.z, 0.0);
}

// A model spawned 0.1 m into another (two 0.2 m boxes 0.1 m apart): one
// warning naming the link, the depth and the other model, on both engines.
TEST_P(ModelServices, ASpawnIntoAnotherModelIsOneWarningWithTheDepth) {
  const std::string backend = GetParam();
  TempDir dir("servoloop-model-overlap-" + backend);
  Node world(node::loadLaunchFile(writeBoxWorld(dir.path(), backend, 1)), pausedOptions());
  world.start();
  node::RobotSpec inside;
  inside.urdf = dir.path() / "box.urdf";
  inside.model = "intruder";
  inside.robot_namespace = "/intruder";
  inside.pose = std::array<double, 6>{0.1, 0.0, 0.1, 0.0, 0.0, 0.0};
  std::vector<std::string> warnings;
  {
    const ThreadLogCapture capture;
    world.spawnRobot(inside);
    warnings = capture.warnings();
  }
  // The depth as the engine's contacts give it: bullet's the overlap, 0.1 m;
  // MuJoCo's box-box collider puts its contact points half way, 0.05 m.
  const std::string depth = backend == "mujoco" ? "0.050" : "0.100";
  int overlaps = 0;
  for (const std::string& warning : warnings) {
    if (warning.find("link 'box' starts " + depth + " m inside robot 'box' link 'box'") != std::string::npos) {
      ++overlaps;
    }
  }
  EXPECT_EQ(overlaps, 1) << ::testing::PrintToString(warnings);
}

INSTANTIATE_TEST_SUITE_P(Engines, ModelServices, ::testing::Values("bullet", "mujoco"));

// Two boxes thrown at the same moment; one deleted in flight while the world
// runs. The other flies on, bit for bit as in a world that only ever had it
// (the two never touch), and the deleted one is gone from every list.
TEST_P(ModelServices, ADeletedModelLeavesTheOthersRunningUnchanged) {
  const std::string backend = GetParam();
  TempDir dir("servoloop-model-delete-" + backend);
  const fs::path launch = writeBoxWorld(dir.path(), backend, 2);

  const auto throwBoxes = [](Node& world, bool two) {
    world.setModelState("box0", poseAt(0.0, 0.0, 2.0), twistOf(0.5, 0.0, 2.0, 1.0));
    if (two) world.setModelState("box1", poseAt(0.6, 0.0, 2.0), twistOf(-0.2, 0.0, 1.0, 0.0));
  };

  // The reference: box1 deleted before anything moved.
  Node alone(node::loadLaunchFile(launch), pausedOptions());
  alone.start();
  EXPECT_EQ(alone.deleteModel("/box1"), "/box1");
  ASSERT_EQ(alone.stepWorld(100), 100u);
  throwBoxes(alone, false);
  ASSERT_EQ(alone.stepWorld(300), 300u);
  const std::vector<double> reference = stateValues(alone.modelState("box0"));
  alone.shutdown();

  // Both at rest for 100 steps (as above: box1 sits apart), both thrown,
  // then box1 deleted while the world runs.
  Node world(node::loadLaunchFile(launch), pausedOptions());
  world.start();
  ASSERT_EQ(world.stepWorld(100), 100u);
  throwBoxes(world, true);
  ASSERT_EQ(world.stepWorld(150), 150u);
  // Running when the model goes, and running on after it went.
  world.unpauseWorld();
  ASSERT_TRUE(stepsPass(world, 250)) << "the world did not run";
  EXPECT_EQ(world.deleteModel("box1"), "/box1");
  ASSERT_TRUE(stepsPass(world, world.worldState().steps)) << "the world stopped when a model was deleted";
  world.pauseWorld();
  EXPECT_EQ(world.robotNamespaces(), std::vector<std::string>{"/box0"});
  EXPECT_EQ(world.findModel("box1"), nullptr);
  EXPECT_THROW(world.modelState("box1"), Error);
  EXPECT_THROW(world.deleteModel("box1"), Error) << "deleted twice";

  // The same history for box0 from a paused world: rerun it in one that
  // deletes box1 at a known step, and compare with the reference.
  Node paused(node::loadLaunchFile(launch), pausedOptions());
  paused.start();
  ASSERT_EQ(paused.stepWorld(100), 100u);
  throwBoxes(paused, false);
  (void)paused.deleteModel("box1");
  ASSERT_EQ(paused.stepWorld(300), 300u);
  const std::vector<double> after = stateValues(paused.modelState("box0"));
  ASSERT_EQ(after.size(), reference.size());
  EXPECT_EQ(std::memcmp(after.data(), reference.data(), after.size() * sizeof(double)), 0)
      << "box0 flew differently once box1 was deleted: z " << after[2] << " vs " << reference[2];
  // And it flew: 0.3 s of free flight from 2 m up at 2 m/s.
  EXPECT_NEAR(after[2], 2.0 + 2.0 * 0.3 - kGravity * 0.09 / 2, 3e-3);
}

}  // namespace
}  // namespace servoloop::world_test
