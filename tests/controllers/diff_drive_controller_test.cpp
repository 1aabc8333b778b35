// diff_drive_controller/DiffDriveController against hand calculations: the
// odometry's exact arc integration against the circle a base with constant
// wheel speeds drives, the speed limiter's velocity, acceleration and jerk
// clamps, wheel speeds from a command, the wheel geometry read from a URDF,
// cmd_vel_timeout, the odom and tf topics, and parameter errors.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "controller_test_support.hpp"
#include "servoloop/controllers/diff_drive_controller/diff_drive_controller.hpp"
#include "servoloop/controllers/diff_drive_controller/odometry.hpp"
#include "servoloop/controllers/diff_drive_controller/speed_limiter.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/description/robot_model.hpp"

namespace servoloop::controllers::diff_drive_controller {
namespace {

using testing::initController;
using testing::makeContext;
using testing::TestJointsHW;
using Twist = servoloop::geometry_msgs::Twist;
using OdometryMsg = servoloop::nav_msgs::Odometry;
using TFMessage = servoloop::tf2_msgs::TFMessage;

constexpr double kDt = 0.001;

TEST(DiffDriveOdometry, ConstantWheelSpeedsDriveTheCircleByHand) {
  // s = 0.4 m, r = 0.05 m; left 6 rad/s, right 14 rad/s: v = r(ωl + ωr)/2 =
  // 0.5 m/s, ω = r(ωr − ωl)/s = 1 rad/s, a circle of radius v/ω = 0.5 m.
  Odometry odometry;
  odometry.resize(10);
  odometry.setWheelParams(0.4, 0.05, 0.05);
  odometry.reset(0.0, 0.0, 0.0);
  double left = 0.0, right = 0.0;
  for (int k = 1; k <= 2000; ++k) {
    left += 6.0 * kDt;
    right += 14.0 * kDt;
    odometry.update(left, right, k * kDt);
  }
  const double t = 2.0, radius = 0.5, w = 1.0;
  EXPECT_NEAR(odometry.heading(), w * t, 1e-9);
  EXPECT_NEAR(odometry.x(), radius * std::sin(w * t), 1e-9);
  EXPECT_NEAR(odometry.y(), radius * (1.0 - std::cos(w * t)), 1e-9);
  EXPECT_NEAR(odometry.linear(), 0.5, 1e-9);
  EXPECT_NEAR(odometry.angular(), 1.0, 1e-9);

  // Straight (equal speeds) and turning in place (opposite speeds).
  odometry.reset(0.0, 0.0, 0.0);
  odometry.update(2.0, 2.0, 0.1);
  EXPECT_NEAR(odometry.x(), 0.1, 1e-12);
  EXPECT_NEAR(odometry.y(), 0.0, 1e-12);
  odometry.reset(0.0, 0.0, 0.0);
  odometry.update(-2.0, 2.0, 0.1);
  EXPECT_NEAR(odometry.heading(), 2.0 * 0.1 / 0.4, 1e-12);  // (0.1 − (−0.1)) / 0.4
  EXPECT_NEAR(odometry.x(), 0.0, 1e-12);
}

TEST(DiffDriveSpeedLimiter, ClampsJerkThenAccelerationThenVelocity) {
  SpeedLimiter limiter;
  limiter.has_velocity_limits = true;
  limiter.min_velocity = -1.0;
  limiter.max_velocity = 1.0;
  double v = 3.0;
  limiter.limit(v, 0.0, 0.0, 0.01);
  EXPECT_DOUBLE_EQ(v, 1.0);
  limiter.has_acceleration_limits = true;
  limiter.min_acceleration = -2.0;
  limiter.max_acceleration = 2.0;
  v = 3.0;
  limiter.limit(v, 0.5, 0.5, 0.01);  // at most 2 m/s² · 0.01 s more
  EXPECT_DOUBLE_EQ(v, 0.52);
  limiter.has_jerk_limits = true;
  limiter.min_jerk = -10.0;
  limiter.max_jerk = 10.0;
  v = 3.0;
  // From constant 0.5: the acceleration may grow by 10 · 2 · 0.01² = 0.002 m/s per step.
  limiter.limit(v, 0.5, 0.5, 0.01);
  EXPECT_NEAR(v, 0.502, 1e-12);
}

// A base with two wheels 0.4 m apart (y = ±0.2), radius 0.05, and a caster.
std::shared_ptr<const urdf::ModelInterface> diffBotModel() {
  const char* inertial =
      R"(<inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>)";
  std::string xml = R"(<?xml version="1.0"?><robot name="diffbot"><link name="base_link">)" + std::string(inertial) +
                    "</link>";
  for (const auto& [side, y] : {std::pair{"left", 0.2}, std::pair{"right", -0.2}}) {
    xml += std::string("<link name=\"") + side + "_wheel\">" + inertial +
           R"(<collision><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision></link>)";
    xml += std::string("<joint name=\"") + side + "_wheel_joint\" type=\"continuous\"><parent link=\"base_link\"/>" +
           "<child link=\"" + side + "_wheel\"/><origin xyz=\"0.1 " + std::to_string(y) +
           " 0.05\" rpy=\"-1.5708 0 0\"/><axis xyz=\"0 0 1\"/></joint>";
  }
  xml += "</robot>";
  return servoloop::parseRobotModel(xml, "diffbot.urdf");
}

class DiffDriveTest : public ::testing::Test {
 protected:
  void init(const std::string& params) {
    initController(controller, hw, makeContext("base", params, &bus, diffBotModel()));
    controller.startRequest(Time(0.0));
  }
  // One cycle; the wheels then turn at their commanded speeds (ideal wheels).
  void step() {
    now += kDt;
    bus.setTime(Time(now));
    controller.update(Time(now), Duration(kDt));
    for (std::size_t i = 0; i < 2; ++i) {
      hw.velocity[i] = hw.velocity_command[i];
      hw.position[i] += kDt * hw.velocity_command[i];
    }
    bus.flush();  // delivers before the publishers' queues (16 messages) fill
  }
  void runFor(double seconds) {
    const double until = now + seconds;
    while (now + 0.5 * kDt < until) step();
  }
  void command(double linear, double angular) {
    Twist twist;
    twist.linear.x = linear;
    twist.angular.z = angular;
    bus.publish("/robot/base/cmd_vel", twist);
  }

  servoloop::realtime::TopicBus bus;
  TestJointsHW hw{{"left_wheel_joint", "right_wheel_joint"}};
  DiffDriveController controller;
  double now = 0.0;
};

TEST_F(DiffDriveTest, WheelGeometryFromTheUrdfAndWheelSpeedsFromACommand) {
  init("{left_wheel: left_wheel_joint, right_wheel: [right_wheel_joint]}");
  EXPECT_DOUBLE_EQ(controller.wheelSeparation(), 0.4);
  EXPECT_DOUBLE_EQ(controller.wheelRadius(), 0.05);
  command(0.5, 1.0);
  step();
  EXPECT_NEAR(hw.velocity_command[0], (0.5 - 1.0 * 0.2) / 0.05, 1e-12);  // 6 rad/s
  EXPECT_NEAR(hw.velocity_command[1], (0.5 + 1.0 * 0.2) / 0.05, 1e-12);  // 14 rad/s
}

TEST_F(DiffDriveTest, OdometryOfAnArcAndTheOdomAndTfTopics) {
  init("{left_wheel: left_wheel_joint, right_wheel: right_wheel_joint, publish_rate: 50, cmd_vel_timeout: 5.0, "
       "pose_covariance_diagonal: [0.001, 0.001, 1000000.0, 1000000.0, 1000000.0, 0.03]}");
  std::vector<OdometryMsg> odom;
  std::vector<TFMessage> tf;
  auto odom_sub = bus.subscribe<OdometryMsg>("/robot/base/odom", [&](const OdometryMsg& m) { odom.push_back(m); });
  auto tf_sub = bus.subscribe<TFMessage>("/tf", [&](const TFMessage& m) { tf.push_back(m); });
  command(0.5, 1.0);
  step();  // taken here; the wheels turn from the next cycle on
  const double start = now;
  runFor(2.0);
  bus.flush();
  // The wheels turned for 2 s at 6 and 14 rad/s: the circle of radius 0.5 m.
  const double t = now - start;
  EXPECT_NEAR(controller.odometry().heading(), t, 1e-9);
  EXPECT_NEAR(controller.odometry().x(), 0.5 * std::sin(t), 1e-9);
  EXPECT_NEAR(controller.odometry().y(), 0.5 * (1.0 - std::cos(t)), 1e-9);
  ASSERT_EQ(odom.size(), 101u);  // 50 Hz over 2.001 s: the first cycle and every 20th
  const OdometryMsg& last = odom.back();
  EXPECT_EQ(last.frame_id, "odom");
  EXPECT_EQ(last.child_frame_id, "base_link");
  EXPECT_NEAR(last.linear.x, 0.5, 1e-9);
  EXPECT_NEAR(last.angular.z, 1.0, 1e-9);
  EXPECT_NEAR(2.0 * std::atan2(last.orientation.z, last.orientation.w), last.stamp - start, 1e-9);
  EXPECT_DOUBLE_EQ(last.pose_covariance[0], 0.001);
  EXPECT_DOUBLE_EQ(last.pose_covariance[35], 0.03);
  EXPECT_DOUBLE_EQ(last.pose_covariance[1], 0.0);
  ASSERT_EQ(tf.size(), odom.size());
  EXPECT_EQ(tf.back().transforms.at(0).child_frame_id, "base_link");
  EXPECT_DOUBLE_EQ(tf.back().transforms.at(0).translation.x, last.position.x);
}

TEST_F(DiffDriveTest, CmdVelTimeoutStopsTheBase) {
  init("{left_wheel: left_wheel_joint, right_wheel: right_wheel_joint, cmd_vel_timeout: 0.25}");
  command(0.5, 0.0);
  runFor(0.2);
  EXPECT_DOUBLE_EQ(hw.velocity_command[0], 10.0);
  runFor(0.1);  // 0.3 s after the command
  EXPECT_DOUBLE_EQ(hw.velocity_command[0], 0.0);
  EXPECT_DOUBLE_EQ(hw.velocity_command[1], 0.0);
}

TEST_F(DiffDriveTest, AccelerationLimitRampsTheCommand) {
  init("{left_wheel: left_wheel_joint, right_wheel: right_wheel_joint, "
       "linear: {x: {has_acceleration_limits: true, max_acceleration: 1.0}}}");
  command(0.5, 0.0);
  runFor(0.1);
  // 1 m/s² for 0.1 s: 0.1 m/s, 2 rad/s at the wheels.
  EXPECT_NEAR(hw.velocity_command[0], 0.1 / 0.05, 1e-9);
}

TEST_F(DiffDriveTest, NonFiniteCommandsAreIgnored) {
  init("{left_wheel: left_wheel_joint, right_wheel: right_wheel_joint}");
  command(0.5, 0.0);
  step();
  command(NAN, 0.0);
  step();
  EXPECT_EQ(controller.rejectedCommands(), 1u);
  EXPECT_DOUBLE_EQ(hw.velocity_command[0], 10.0);
}

TEST(DiffDriveParameters, ErrorsNameTheParameter) {
  servoloop::realtime::TopicBus bus;
  TestJointsHW hw({"left_wheel_joint", "right_wheel_joint"});
  std::vector<testing::hi::InterfaceResources> claimed;
  const auto error = [&](const std::string& params, std::shared_ptr<const urdf::ModelInterface> model) {
    DiffDriveController controller;
    try {
      controller.initRequest(&hw, makeContext("base", params, &bus, std::move(model)), claimed);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_THAT(error("{left_wheel: left_wheel_joint, right_wheel: right_wheel_joint}", nullptr),
              ::testing::HasSubstr("wheel_separation' is missing"));
  EXPECT_THAT(error("{left_wheel: [left_wheel_joint], right_wheel: [right_wheel_joint, left_wheel_joint]}",
                    diffBotModel()),
              ::testing::HasSubstr("give as many on each side"));
  EXPECT_THAT(error("{left_wheel: left_wheel_joint, right_wheel: right_wheel_joint, wheel_radius: -1}", diffBotModel()),
              ::testing::HasSubstr("wheel_radius' is -1"));
  EXPECT_THAT(error("{left_wheel: left_wheel_joint, right_wheel: right_wheel_joint, "
                    "linear: {x: {max_velocity: 1.0, min_velocity: 2.0}}}",
                    diffBotModel()),
              ::testing::HasSubstr("min_velocity"));
}

// A window sizes what the controller allocates at load: a huge one is one
// error naming the parameter, the value and the limit, before any allocation.
TEST(DiffDriveParameters, VelocityRollingWindowSizeIsBounded) {
  servoloop::realtime::TopicBus bus;
  TestJointsHW hw({"left_wheel_joint", "right_wheel_joint"});
  std::vector<testing::hi::InterfaceResources> claimed;
  const auto error = [&](const std::string& window) {
    DiffDriveController controller;
    try {
      controller.initRequest(&hw,
                             makeContext("base",
                                         "{left_wheel: left_wheel_joint, right_wheel: right_wheel_joint, "
                                         "velocity_rolling_window_size: " + window + "}",
                                         &bus, diffBotModel()),
                             claimed);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string huge = error("1000000000");
  EXPECT_THAT(huge, ::testing::HasSubstr("base/velocity_rolling_window_size' is '1000000000'"));
  EXPECT_THAT(huge, ::testing::HasSubstr("from 1 to " + std::to_string(DiffDriveController::kMaxVelocityWindow)));
  EXPECT_THAT(huge, ::testing::HasSubstr("velocity_rolling_window_size: 10"));
  EXPECT_THAT(error("0"), ::testing::HasSubstr("is '0'"));
  EXPECT_THAT(error("-5"), ::testing::HasSubstr("is '-5'"));
  EXPECT_THAT(error("2.5"), ::testing::HasSubstr("whole number"));
  EXPECT_EQ(error("10"), "");
  EXPECT_EQ(error(std::to_string(DiffDriveController::kMaxVelocityWindow)), "");
}

}  // namespace
}  // namespace servoloop::controllers::diff_drive_controller
