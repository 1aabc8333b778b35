// The mujoco backend as users get it: loaded by type name "mujoco" from the
// build's plugin folder, driven through RobotHW/SimulatedRobotHW only.
#include <gtest/gtest.h>

#include "backend_plugin_check.hpp"

namespace servoloop::sim_mujoco {
namespace {

TEST(MujocoBackendPlugin, LoadsByTypeNameAndRunsTheSeedRobot) {
  sim_testing::expectSeedRobotRunsOnPlugin(SERVOLOOP_PLUGIN_DIR, "mujoco");
}

}  // namespace
}  // namespace servoloop::sim_mujoco
