// Zero allocations on the control thread: 100,000 updates of a
// JointStateController publishing at 50 Hz and the seed's
// effort_controllers/JointPositionController (state topic every 10th update)
// receiving a new setpoint from another thread every 100 cycles, with the
// bus's delivery thread running. Also the raw PD and a group controller.
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
    published.store(n);
  }
  control.join();
  bus.stop();

  EXPECT_EQ(allocations, 0u);
  const int last = kCycles / kCommandEvery;
  EXPECT_DOUBLE_EQ(final_setpoint, 0.25 + 1.5 * static_cast<double>(last % 7) / 6.0);
  EXPECT_DOUBLE_EQ(hw.effort_command[2], final_setpoint);  // the group's last command
  // One timeout before the first command (t = 0.05 s), then one 0.05 s after
  // each command but the last (which came in the final cycle).
  EXPECT_EQ(group.commandTimeouts(), static_cast<std::uint64_t>(kCycles / kCommandEvery));
  // 50 Hz over 100 s of control time: the first cycle, then every 20th.
  EXPECT_EQ(joint_states.publishedCount(), static_cast<std::uint64_t>(kCycles / 20));
  EXPECT_GT(joint_state_messages, 0u);
}

}  // namespace
}  // namespace servoloop::controllers
