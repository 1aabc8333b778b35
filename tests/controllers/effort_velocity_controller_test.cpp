// effort_controllers/JointVelocityController: effort = PID(v_cmd - v, dt).
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "controller_test_support.hpp"
#include "servoloop/controllers/effort_controllers/joint_velocity_controller.hpp"

namespace servoloop::controllers {
namespace {

using effort_controllers::JointVelocityController;
using testing::initController;
using testing::makeContext;
using testing::TestJointsHW;
using Float64 = servoloop::std_msgs::Float64;
using StateMsg = servoloop::control_msgs::JointControllerState;

TEST(EffortVelocityController, PidOnTheVelocityErrorStartingFromZero) {
  servoloop::realtime::TopicBus bus;
  TestJointsHW hw({"wheel"});
  JointVelocityController controller;
  initController(controller, hw,
                 makeContext("vel", "{joint: wheel, pid: {p: 4.0, i: 1.0, d: 0.01, i_clamp: 2.0}}", &bus));
  std::vector<StateMsg> states;
  auto subscription = bus.subscribe<StateMsg>("/robot/vel/state",
                                              [&](const StateMsg& msg) { states.push_back(msg); });
  hw.velocity[0] = 0.5;
  controller.startRequest(Time(0.0));

  // No command yet: the setpoint is 0, so the error is -v.
  const double dt = 0.01;
  double error = 0.0 - 0.5;
  double integral = dt * error;
  double expected = 4.0 * error + 1.0 * integral + 0.01 * (error - 0.0) / dt;
  controller.update(Time(dt), Duration(dt));
  EXPECT_DOUBLE_EQ(controller.velocitySetpoint(), 0.0);
  EXPECT_NEAR(hw.effort_command[0], expected, 1e-12);

  bus.publish("/robot/vel/command", Float64{2.0});
  const double previous_error = error;
  error = 2.0 - 0.5;
  integral += dt * error;
  expected = 4.0 * error + 1.0 * integral + 0.01 * (error - previous_error) / dt;
  controller.update(Time(2 * dt), Duration(dt));
  EXPECT_DOUBLE_EQ(controller.velocitySetpoint(), 2.0);
  EXPECT_NEAR(hw.effort_command[0], expected, 1e-12);

  bus.publish("/robot/vel/command", Float64{std::numeric_limits<double>::quiet_NaN()});
  controller.update(Time(3 * dt), Duration(dt));
  EXPECT_DOUBLE_EQ(controller.velocitySetpoint(), 2.0);
  EXPECT_EQ(controller.rejectedNonFiniteCommands(), 1u);

  for (int k = 4; k <= 12; ++k) controller.update(Time(k * dt), Duration(dt));
  bus.flush();
  ASSERT_EQ(states.size(), 2u);  // updates 1 and 11
  EXPECT_DOUBLE_EQ(states[0].set_point, 0.0);
  EXPECT_DOUBLE_EQ(states[0].process_value, 0.5);
  EXPECT_DOUBLE_EQ(states[0].error, -0.5);
  EXPECT_DOUBLE_EQ(states[1].set_point, 2.0);
  EXPECT_DOUBLE_EQ(states[1].p, 4.0);
  EXPECT_DOUBLE_EQ(states[1].i_clamp, 2.0);
}

}  // namespace
}  // namespace servoloop::controllers
