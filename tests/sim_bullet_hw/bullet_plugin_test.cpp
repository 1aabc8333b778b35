// The bullet backend as users get it: loaded by type name "bullet" from the
// build's plugin folder, driven through RobotHW/SimulatedRobotHW only.
#include <gtest/gtest.h>

#include "backend_plugin_check.hpp"

namespace servoloop::sim_bullet {
namespace {

TEST(BulletBackendPlugin, LoadsByTypeNameAndRunsTheSeedRobot) {
  sim_testing::expectSeedRobotRunsOnPlugin(SERVOLOOP_PLUGIN_DIR, "bullet");
}

}  // namespace
}  // namespace servoloop::sim_bullet
