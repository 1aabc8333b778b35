#pragma once
// The check every physics backend's plugin test runs: the backend loaded as
// users get it and driven on the seed robot.
#include <string>

#include <gtest/gtest.h>

#include "servoloop/plugin/plugin_loader.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/hardware_interface/simulated_robot_hw.hpp"
#include "sim_test_support.hpp"

namespace servoloop::sim_testing {

// The backend `type` as users get it: loaded by its type name from
// plugin_dir and driven through RobotHW/SimulatedRobotHW only, on the seed
// robot with a 2 ms step and 50 N·m asked of its 10 N·m joint.
inline void expectSeedRobotRunsOnPlugin(const std::string& plugin_dir, const std::string& type) {
  namespace hi = hardware_interface;
  servoloop::plugin::PluginLoader loader({plugin_dir});
  auto robot = loader.create<hi::RobotHW>(type);
  ASSERT_NE(robot, nullptr);
  auto* simulated = dynamic_cast<hi::SimulatedRobotHW*>(robot.get());
  ASSERT_NE(simulated, nullptr) << "the " << type << " backend is a SimulatedRobotHW";

  const std::string path = seedUrdfPath(true);
  robot->init(makeInfo(readFile(path), "sim: {time_step: 0.002}", path));
  EXPECT_DOUBLE_EQ(simulated->timeStep().seconds, 0.002);
  const auto controller = controllerClaiming("c", "EffortJointInterface", {"joint1"});
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

}  // namespace servoloop::sim_testing
