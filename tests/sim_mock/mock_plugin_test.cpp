// The mock backend as users get it: loaded by type name "mock" from the
// build's plugin folder, then driven through the RobotHW/SimulatedRobotHW interface.
#include <gtest/gtest.h>

#include "servoloop/plugin/plugin_loader.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/hardware_interface/simulated_robot_hw.hpp"
#include "sim_test_support.hpp"

namespace servoloop::sim_mock {
namespace {

namespace hi = hardware_interface;
using sim_testing::armUrdf;
using sim_testing::controllerClaiming;
using sim_testing::makeInfo;

constexpr Duration kPeriod(0.001);

TEST(MockBackendPlugin, LoadsByTypeNameFromThePluginFolder) {
  servoloop::plugin::PluginLoader loader({SERVOLOOP_PLUGIN_DIR});
  auto robot = loader.create<hi::RobotHW>("mock");
  ASSERT_NE(robot, nullptr);
  auto* simulated = dynamic_cast<hi::SimulatedRobotHW*>(robot.get());
  ASSERT_NE(simulated, nullptr) << "the mock backend is a SimulatedRobotHW";
  robot->init(makeInfo(armUrdf(1.0, sim_testing::kAllJointInterfaces)));
  robot->doSwitch({controllerClaiming("v", "VelocityJointInterface", {"arm_joint"})}, {});
  hi::JointHandle handle = robot->get<hi::VelocityJointInterface>()->getHandle("arm_joint");
  for (int k = 0; k < 100; ++k) {
    robot->read(Time(), kPeriod);
    handle.setCommand(1.0);
    robot->write(Time(), kPeriod);
    simulated->step();
  }
  robot->read(Time(), kPeriod);
  EXPECT_NEAR(handle.getPosition(), 0.1, 1e-12);
}

}  // namespace
}  // namespace servoloop::sim_mock
