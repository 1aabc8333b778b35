// The mujoco backend as users get it: loaded by type name "mujoco" from the
// build's plugin folder, driven through RobotHW/SimulatedRobotHW only.
#include <gtest/gtest.h>

#include "servoloop/controller_manager/plugin_loader.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/hardware_interface/simulated_robot_hw.hpp"
#include "sim_test_support.hpp"

namespace servoloop::sim_mujoco {
namespace {

namespace hi = hardware_interface;

TEST(MujocoBackendPlugin, LoadsByTypeNameAndRunsTheSeedRobot) {
  controller_manager::PluginLoader loader({SERVOLOOP_PLUGIN_DIR});
  auto robot = loader.create<hi::RobotHW>("mujoco");
  ASSERT_NE(robot, nullptr);
  auto* simulated = dynamic_cast<hi::SimulatedRobotHW*>(robot.get());
  ASSERT_NE(simulated, nullptr) << "the mujoco backend is a SimulatedRobotHW";

  const std::string path = sim_testing::seedUrdfPath(true);
  robot->init(sim_testing::makeInfo(sim_testing::readFile(path), "sim: {time_step: 0.002}", path));
  EXPECT_DOUBLE_EQ(simulated->timeStep().seconds, 0.002);
  const auto controller = sim_testing::controllerClaiming("c", "EffortJointInterface", {"joint1"});
  ASSERT_TRUE(robot->prepareSwitch({controller}, {}));
  robot->doSwitch({controller}, {});
  hi::JointHandle handle = robot->get<hi::EffortJointInterface>()->getHandle("joint1");
  // 5 steps of 2 ms: the joint stays below its 0.5 rad/s limit (10 N·m / 0.35 kg·m² · 10 ms
  // = 0.29 rad/s), beyond which effort saturation would stop pushing.
  for (int k = 0; k < 5; ++k) {
    robot->read(simulated->simTime(), simulated->timeStep());
    handle.setCommand(50.0);
    robot->write(simulated->simTime(), simulated->timeStep());
    simulated->step();
  }
  robot->read(simulated->simTime(), simulated->timeStep());
  EXPECT_NEAR(simulated->simTime().seconds, 0.01, 1e-12);
  EXPECT_DOUBLE_EQ(handle.getEffort(), 10.0);
  EXPECT_GT(handle.getPosition(), 0.0);
}

}  // namespace
}  // namespace servoloop::sim_mujoco
