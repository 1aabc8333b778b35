// Contact that holds things (robots/gripper_arm): the gantry arm's gripper
// closes on a free 5 cm cube, the arm lifts it 0.2 m and carries it 0.3 m
// sideways, on bullet and on mujoco. The gripper action ends as
// ros_controllers' GripperActionController ends it on an object (stalled, not
// reached_goal: aborted) with the gap between the fingers at the cube's
// width, and the cube stays within 5 mm of where the fingers took it.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "servoloop/node/action_json.hpp"
#include "servoloop/node/node.hpp"

namespace servoloop::world_test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kCube = 0.05;           // m, the cube's side
constexpr double kHandReach = 0.4;       // m, the hand's x
constexpr double kFingerMidHeight = 0.03;  // m below the hand's joint frame: the fingers' middle
constexpr double kLiftOrigin = 0.06;     // m, the hand's height at lift 0

double joint(node::RobotInstance& robot, const std::string& name) {
  for (const node::JointReading& reading : robot.joints()) {
    if (reading.name == name) return reading.position;
  }
  ADD_FAILURE() << "no joint " << name;
  return NAN;
}

// Steps the paused world until the goal ends (at most `seconds`).
realtime::GoalState stepUntilDone(node::Node& world, const realtime::ActionGoal& goal, double seconds) {
  for (double t = 0.0; t < seconds; t += 0.05) {
    const realtime::GoalState state = goal.state();
    if (state != realtime::GoalState::pending && state != realtime::GoalState::active) return state;
    EXPECT_EQ(world.stepWorld(50), 50u);
  }
  return goal.state();
}

// The cube's centre relative to the point between the fingertips' middles.
std::array<double, 3> cubeInHand(node::Node& world, node::RobotInstance& arm) {
  const node::ModelState cube = world.modelState("cube");
  return {cube.position[0] - kHandReach, cube.position[1] - joint(arm, "slide_joint"),
          cube.position[2] - (kLiftOrigin + joint(arm, "lift_joint") - kFingerMidHeight)};
}

class GripperArm : public ::testing::TestWithParam<std::string> {};

TEST_P(GripperArm, PicksUpACubeAndCarriesIt) {
  const std::string backend = GetParam();
#ifndef SERVOLOOP_TEST_MUJOCO
  if (backend == "mujoco") GTEST_SKIP() << "built without MuJoCo (libmujoco-dev)";
#endif
  node::LaunchFile launch =
      node::loadLaunchFile(fs::path(SERVOLOOP_SOURCE_DIR) / "robots" / "gripper_arm" / "gripper_arm.launch.yaml");
  launch.world.backend = backend;
  node::NodeOptions options;
  options.serve_ipc = false;
  options.real_time_factor = 0.0;
  options.start_paused = true;
  node::Node world(launch, options);
  world.start();
  node::RobotInstance& arm = *world.findRobot("/gripper_arm");
  ASSERT_EQ(world.stepWorld(300), 300u);
  EXPECT_NEAR(world.modelState("cube").position[2], kCube / 2, 1e-3) << "the cube rests on the ground";
  EXPECT_GT(2 * joint(arm, "finger_joint"), kCube + 0.02) << "the fingers start open, wider than the cube";

  // Close to a gap of 0 with at most 10 N: the cube stops the fingers.
  const auto grip = node::sendGoalJson(arm.actions(), "/gripper_arm/gripper_controller/gripper_cmd", "",
                                       json{{"command", {{"position", 0.0}, {"max_effort", 10.0}}}});
  ASSERT_EQ(stepUntilDone(world, *grip, 5.0), realtime::GoalState::aborted);
  const json result = node::resultJson("control_msgs/GripperCommand", *grip);
  EXPECT_EQ(result.value("stalled", false), true) << result.dump();
  EXPECT_EQ(result.value("reached_goal", true), false) << result.dump();
  // MuJoCo's soft contacts let the 10 N squeeze press each finger about 1 mm in.
  EXPECT_NEAR(2 * joint(arm, "finger_joint"), kCube, backend == "mujoco" ? 2.5e-3 : 1e-3)
      << "the gap is the cube's width";
  const std::array<double, 3> held = cubeInHand(world, arm);

  // Lift 0.2 m in 2 s, then 0.3 m sideways in 2 s.
  const auto carry = node::sendGoalJson(
      arm.actions(), "/gripper_arm/arm_controller/follow_joint_trajectory", "",
      json{{"trajectory",
            {{"joint_names", {"lift_joint", "slide_joint"}},
             {"points",
              {{{"positions", {0.2, 0.0}}, {"time_from_start", 2.0}},
               {{"positions", {0.2, 0.3}}, {"time_from_start", 4.0}}}}}}});
  ASSERT_EQ(stepUntilDone(world, *carry, 10.0), realtime::GoalState::succeeded);
  ASSERT_EQ(world.stepWorld(200), 200u);
  EXPECT_NEAR(joint(arm, "lift_joint"), 0.2, 0.005);
  EXPECT_NEAR(joint(arm, "slide_joint"), 0.3, 0.005);
  const node::ModelState cube = world.modelState("cube");
  EXPECT_NEAR(cube.position[1], 0.3, 0.005) << "carried sideways";
  EXPECT_GT(cube.position[2], kCube / 2 + 0.19) << "lifted";
  const std::array<double, 3> now = cubeInHand(world, arm);
  EXPECT_LT(std::hypot(now[0] - held[0], now[1] - held[1], now[2] - held[2]), 0.005)
      << "the cube moved in the hand by (" << now[0] - held[0] << ", " << now[1] - held[1] << ", "
      << now[2] - held[2] << ") m";
}

INSTANTIATE_TEST_SUITE_P(Engines, GripperArm, ::testing::Values("bullet", "mujoco"));

}  // namespace
}  // namespace servoloop::world_test
