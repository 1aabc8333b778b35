// The world loop's cycles allocate nothing with several robots in one world,
// touching, on bullet and on mujoco: the wheeled base pushing a row of three 0.3 kg boxes (its diff
// drive and joint state controllers publishing, timed cmd_vel publications
// between segments; the first box with a contact sensor), and the seed arm
// with its IMU and joint force-torque sensor swinging under its position
// controller, ros_controllers' sensor controllers publishing them. Counted on the world's thread, over its segments of cycles
// (the real-time part), through operator new and the engine's own allocator
// hook (Bullet's, MuJoCo's mju_user_malloc); and with a browser page open,
// the view's snapshots taken between segments allocate nothing either.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <optional>
#include <thread>
#include <vector>

#include "alloc_counter.hpp"
#include "bullet_alloc_hook.hpp"
#include "servoloop/hardware_interface/contact_sensor_interface.hpp"
#include "servoloop/hardware_interface/imu_sensor_interface.hpp"
#include "servoloop/node/launch_file.hpp"
#include "servoloop/node/robot_instance.hpp"
#include "servoloop/node/world_snapshot.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/world/world_loop.hpp"
#include "temp_dir.hpp"
#include "wait_until.hpp"
#include "world_test_support.hpp"

#ifdef SERVOLOOP_TEST_MUJOCO
#include <mujoco/mujoco.h>
#endif

namespace servoloop::world_test {
namespace {

namespace bullet_alloc = servoloop::testing::bullet_alloc;

// MuJoCo's allocations, all and those while counting (as bullet_alloc's).
namespace mujoco_alloc {
std::atomic<std::size_t> all{0};
std::atomic<std::size_t> counted{0};
std::atomic<bool> counting{false};
#ifdef SERVOLOOP_TEST_MUJOCO
void* countingAlloc(std::size_t size) {
  all.fetch_add(1, std::memory_order_relaxed);
  if (counting.load(std::memory_order_relaxed)) counted.fetch_add(1, std::memory_order_relaxed);
  return std::aligned_alloc(64, (size + 63) / 64 * 64);  // MuJoCo's own alignment
}
void release(void* p) { std::free(p); }
// Installed before any MuJoCo object exists (the plugin shares libmujoco's hook).
const bool kInstalled = [] {
  mju_user_malloc = countingAlloc;
  mju_user_free = release;
  return true;
}();
#endif
}  // namespace mujoco_alloc

class WorldAllocation : public ::testing::TestWithParam<std::string> {};

TEST_P(WorldAllocation, CyclesOfSeveralRobotsInContactAllocateNothing) {
  const std::string backend = GetParam();
#ifndef SERVOLOOP_TEST_MUJOCO
  if (backend == "mujoco") GTEST_SKIP() << "built without MuJoCo (libmujoco-dev)";
#endif
  ASSERT_TRUE(bullet_alloc::kInstalled);
  servoloop::testing::TempDir dir("servoloop-world-alloc-" + backend);
  servoloop::testing::writeFile(dir.path() / "box.urdf", boxUrdf(0.2, 0.3, 0.5));
  std::string sensed_box = boxUrdf(0.2, 0.3, 0.5);
  sensed_box.replace(sensed_box.find("</robot>"), 8, R"(<gazebo reference="box"><sensor name="bumper" type="contact">
    <contact><collision>box_collision</collision></contact></sensor></gazebo>
</robot>)");
  servoloop::testing::writeFile(dir.path() / "sensed_box.urdf", sensed_box);
  const fs::path source(SERVOLOOP_SOURCE_DIR);
  // The base and the boxes drive along y = kLane, clear of the seed arm,
  // which is fixed to the world at the origin.
  constexpr double kLane = 3.0;

  auto plugins = std::make_shared<plugin::PluginLoader>();
  params::ParameterStore store;
  store.loadFile((source / "robots/diff_bot/control_config/diff_bot_controllers.yaml").string(), "/");
  store.loadFile((source / "robots/one_dof/control_config/one_dof_ctl_params.yaml").string(), "/");
  store.loadFile((source / "robots/one_dof/control_config/sensor_controllers.yaml").string(), "/");

  auto world = plugins->create<hardware_interface::SimulatedWorld>(backend + "/world");
  world->init({0.001, {0.0, 0.0, -9.81}, true});
  ASSERT_TRUE(world->robotsTouch());

  // Counting starts once the base has met the boxes (Bullet sizes its
  // contact pairs and solver arrays for the contacts it has seen).
  constexpr std::uint64_t kCountFromStep = 2500;
  std::optional<servoloop::testing::AllocationCounter> counter;
  std::size_t allocations = 0;
  std::size_t counted_segments = 0;
  world::WorldLoop* loop_ptr = nullptr;
  world::WorldLoopOptions options;
  options.before_segment = [&] {
    if (loop_ptr->steps() < kCountFromStep) return;
    counter.emplace();  // this (the world's) thread
    bullet_alloc::counting = true;
    mujoco_alloc::counting = true;
  };
  options.after_segment = [&] {
    if (!counter) return;
    bullet_alloc::counting = false;
    mujoco_alloc::counting = false;
    allocations += counter->allocations();
    if (counter->allocations() != 0) servoloop::testing::AllocationCounter::printFirstCountedStack();
    counter.reset();
    ++counted_segments;
  };
  world::WorldLoop loop(*world, options);
  loop_ptr = &loop;

  // A browser page open: the world's snapshots for the view taken between
  // segments (counted too) while a reader copies them all the time.
  node::WorldSnapshot snapshot(0.001);
  std::size_t snapshot_allocations = 0;
  std::size_t snapshots_counted = 0;
  struct CountedSnapshots final : world::WorldObserver {
    node::WorldSnapshot* inner = nullptr;
    std::size_t* allocations = nullptr;
    std::size_t* counted = nullptr;
    std::uint64_t betweenSegments(std::uint64_t steps) override {
      if (steps < kCountFromStep) return inner->betweenSegments(steps);
      servoloop::testing::AllocationCounter count;
      const std::uint64_t next = inner->betweenSegments(steps);
      *allocations += count.allocations();
      ++*counted;
      return next;
    }
  } counted_snapshots;
  counted_snapshots.inner = &snapshot;
  counted_snapshots.allocations = &snapshot_allocations;
  counted_snapshots.counted = &snapshots_counted;
  loop.addObserver(counted_snapshots);

  node::RobotWorld robot_world;
  robot_world.plugins = plugins;
  robot_world.parameters = &store;
  robot_world.world.backend = backend;
  robot_world.world.ground_plane = true;
  robot_world.update_rate_hz = 1000.0;
  robot_world.simulated_world = world.get();
  robot_world.world_loop = &loop;

  std::vector<std::unique_ptr<node::RobotInstance>> robots;
  node::RobotSpec base;
  base.urdf = source / "robots/diff_bot/diff_bot.urdf";
  base.robot_namespace = "/diff_bot";
  base.pose = std::array<double, 6>{0, kLane, 0.1, 0, 0, 0};
  base.controllers = {"joint_state_controller", "diff_drive_controller"};
  robots.push_back(std::make_unique<node::RobotInstance>(base, robot_world));
  for (int i = 0; i < 3; ++i) {
    node::RobotSpec box;
    box.urdf = dir.path() / (i == 0 ? "sensed_box.urdf" : "box.urdf");
    box.robot_namespace = "/box" + std::to_string(i);
    box.pose = std::array<double, 6>{0.6 + 0.21 * i, kLane, 0.1, 0, 0, 0};
    robots.push_back(std::make_unique<node::RobotInstance>(box, robot_world));
  }
  node::RobotSpec arm;
  arm.urdf = source / "robots/one_dof/one_dof_sensors.urdf.xacro";
  arm.controllers = {"joint_state_controller", "joint1_position_controller", "imu_sensor_controller",
                     "force_torque_sensor_controller"};
  robots.push_back(std::make_unique<node::RobotInstance>(arm, robot_world));

  for (double t = 0.5; t < 6.0; t += 0.25) {
    robots.front()->addTimedPublication(node::makeTimedPublication(
        "/diff_bot/diff_drive_controller/cmd_vel", "geometry_msgs/Twist", {{"linear", {{"x", 0.4}}}}, t, "test"));
  }
  for (double t = 0.0; t < 6.0; t += 1.0) {
    robots.back()->addTimedPublication(node::makeTimedPublication(
        "/one_DOF_robot/joint1_position_controller/command", "std_msgs/Float64", t < 0.5 ? 1.0 : -t / 6.0, t,
        "test"));
  }

  std::vector<node::WorldSnapshot::Model> snapshot_models;
  for (const auto& robot : robots) {
    node::WorldSnapshot::Model model;
    model.ns = robot->robotNamespace();
    auto* simulated = dynamic_cast<hardware_interface::SimulatedRobotHW*>(&robot->hardware());
    hardware_interface::BaseGroundTruth probe;
    if (simulated != nullptr && simulated->readBaseGroundTruth(probe)) model.floating = simulated;
    if (auto* state = robot->hardware().get<hardware_interface::JointStateInterface>()) {
      for (const std::string& joint : state->getNames()) {
        model.joint_names.push_back(joint);
        model.joint_positions.push_back(state->getHandle(joint).getPositionPtr());
      }
    }
    snapshot_models.push_back(std::move(model));
  }
  snapshot.setModels(std::move(snapshot_models), 0);
  snapshot.enable();
  std::atomic<bool> reading{true};
  std::uint64_t frames_read = 0;
  std::thread reader([&] {
    node::WorldSnapshot::Frame frame;
    while (reading) {
      snapshot.read(frame);
      if (frame.steps > 0) ++frames_read;
      std::this_thread::yield();
    }
  });

  loop.start();
  for (const auto& robot : robots) robot->start(6.0);
  ASSERT_TRUE(servoloop::testing::waitUntil(
      [&] {
        for (const auto& robot : robots) {
          if (!robot->finished()) return false;
        }
        return true;
      },
      std::chrono::seconds(120)));
  loop.stop();
  reading = false;
  reader.join();

  EXPECT_EQ(allocations, 0u);
  EXPECT_EQ(snapshot_allocations, 0u) << "the view's snapshots allocated on the world's thread";
  EXPECT_GT(snapshots_counted, 100u);
  EXPECT_GT(frames_read, 0u);
  // The last snapshot holds the world's state: the first box where the
  // engine has it, to the snapshots' period (1/60 s at < 1 m/s).
  node::WorldSnapshot::Frame last;
  snapshot.read(last);
  EXPECT_GT(last.steps, 5900u);
  if (backend == "bullet") {
    ASSERT_GT(bullet_alloc::all.load(), 0u) << "the hook must see Bullet's allocations";
    EXPECT_EQ(bullet_alloc::counted.load(), 0u) << "Bullet allocated during the world's cycles";
  } else {
    ASSERT_GT(mujoco_alloc::all.load(), 0u) << "the hook must see MuJoCo's allocations";
    EXPECT_EQ(mujoco_alloc::counted.load(), 0u) << "MuJoCo allocated during the world's cycles";
  }
  EXPECT_GT(counted_segments, 100u);
  // The cycles counted were the real thing: the base pushed the row of boxes.
  hardware_interface::BaseGroundTruth first_box;
  auto* box_hw = dynamic_cast<hardware_interface::SimulatedRobotHW*>(&robots[1]->hardware());
  ASSERT_NE(box_hw, nullptr);
  ASSERT_TRUE(box_hw->readBaseGroundTruth(first_box));
  EXPECT_GT(first_box.position[0], 0.6 + 0.5);
  EXPECT_NEAR(last.models[1].pose[0], first_box.position[0], 0.02);
  EXPECT_NEAR(last.models[1].pose[1], first_box.position[1], 0.02);
  // The sensors were sampled: the box's contact sensor holds its contacts,
  // the arm's IMU reads at least gravity.
  auto* contacts = box_hw->get<hardware_interface::ContactSensorInterface>();
  ASSERT_NE(contacts, nullptr);
  EXPECT_GT(contacts->getHandle("bumper").getReading().count, 0u);
  auto* imus = robots.back()->hardware().get<hardware_interface::ImuSensorInterface>();
  ASSERT_NE(imus, nullptr);
  const double* specific_force = imus->getHandle("imu").getLinearAcceleration();
  EXPECT_GT(std::hypot(specific_force[0], specific_force[1], specific_force[2]), 9.0);

  for (const auto& robot : robots) EXPECT_NEAR(robot->simTime(), 6.0, 1e-9) << robot->robotNamespace();
}

INSTANTIATE_TEST_SUITE_P(Engines, WorldAllocation, ::testing::Values("bullet", "mujoco"));

}  // namespace
}  // namespace servoloop::world_test
