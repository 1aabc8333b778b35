#include "servoloop/controllers/diff_drive_controller/diff_drive_controller.hpp"

#include <array>
#include <cmath>

#include "servoloop/controllers/common/controller_params.hpp"
#include "servoloop/controllers/common/joint_handles.hpp"
#include "servoloop/controllers/diff_drive_controller/wheel_geometry.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/plugin/plugin_register.hpp"
#include "servoloop/realtime/topic_bus.hpp"

namespace servoloop::controllers::diff_drive_controller {

namespace cm = controller_manager;

namespace {

// `left_wheel: name` or `left_wheel: [name, ...]`.
std::vector<std::string> wheelNames(const cm::ControllerContext& context, const std::string& key) {
  const params::Parameters value = context.params.child(key);
  if (!value.empty() && value.isScalar()) return {value.as<std::string>()};
  return requireStringList(context, key, key + ": " + key + "_joint");
}

std::array<double, 6> diagonal(const cm::ControllerContext& context, const std::string& key) {
  std::array<double, 6> values{};
  const params::Parameters value = context.params.child(key);
  if (value.empty()) return values;
  if (!value.isList() || value.size() != 6) {
    throw ConfigError("controller '" + context.name + "': parameter '" + parameterPath(context, key) +
                      "' must be a list of 6 numbers (x, y, z, roll, pitch, yaw)");
  }
  for (std::size_t i = 0; i < 6; ++i) {
    values[i] = numberAt(value.item(i), parameterPath(context, key) + "[" + std::to_string(i) + "]", 0.0);
  }
  return values;
}

double mean(const std::vector<hardware_interface::JointHandle>& wheels) noexcept {
  double sum = 0.0;
  for (const auto& wheel : wheels) sum += wheel.getPosition();
  return sum / static_cast<double>(wheels.size());
}

}  // namespace

bool DiffDriveController::init(hardware_interface::VelocityJointInterface* hw, const cm::ControllerContext& context) {
  const std::vector<std::string> left = wheelNames(context, "left_wheel");
  const std::vector<std::string> right = wheelNames(context, "right_wheel");
  if (left.size() != right.size()) {
    throw ConfigError("controller '" + context.name + "': left_wheel names " + std::to_string(left.size()) +
                      " wheel(s) and right_wheel " + std::to_string(right.size()) + "; give as many on each side");
  }
  const auto fromUrdf = [&](const char* key) {
    if (!context.robot_model) {
      throw ConfigError("controller '" + context.name + "': parameter '" + parameterPath(context, key) +
                        "' is missing and there is no robot description to read it from; give it");
    }
  };
  if (context.params.child("wheel_separation").empty()) {
    fromUrdf("wheel_separation");
    wheel_separation_ = wheelSeparationFromUrdf(*context.robot_model, left.front(), right.front(), context.name);
  } else {
    wheel_separation_ = optionalPositive(context, "wheel_separation", 0.0);
  }
  if (context.params.child("wheel_radius").empty()) {
    fromUrdf("wheel_radius");
    wheel_radius_ = wheelRadiusFromUrdf(*context.robot_model, left.front(), context.name);
  } else {
    wheel_radius_ = optionalPositive(context, "wheel_radius", 0.0);
  }
  separation_multiplier_ = optionalPositive(context, "wheel_separation_multiplier", 1.0);
  const double radius_multiplier = optionalPositive(context, "wheel_radius_multiplier", 1.0);
  left_radius_multiplier_ = optionalPositive(context, "left_wheel_radius_multiplier", radius_multiplier);
  right_radius_multiplier_ = optionalPositive(context, "right_wheel_radius_multiplier", radius_multiplier);
  cmd_vel_timeout_ = optionalPositive(context, "cmd_vel_timeout", 0.5);
  timeout_.init(context, "the base brakes to a stop within the acceleration limits", "cmd_vel_timeout", 0.5,
                "cmd_vel");
  open_loop_ = optionalBool(context, "open_loop", false);
  publish_tf_ = optionalBool(context, "enable_odom_tf", true);
  publish_gate_.setRate(optionalPositive(context, "publish_rate", 50.0));
  // The samples are allocated here and summed every cycle: bounded.
  odometry_.resize(optionalCount(context, "velocity_rolling_window_size", kDefaultVelocityWindow, 1,
                                 kMaxVelocityWindow,
                                 "give e.g. velocity_rolling_window_size: 10 (ros_controllers' default; " +
                                     std::to_string(kMaxVelocityWindow) +
                                     " samples already average over 1 s at 1 kHz)"));
  linear_limiter_ = SpeedLimiter::fromParams(context, "linear/x");
  angular_limiter_ = SpeedLimiter::fromParams(context, "angular/z");
  const std::array<double, 6> pose_diagonal = diagonal(context, "pose_covariance_diagonal");
  const std::array<double, 6> twist_diagonal = diagonal(context, "twist_covariance_diagonal");
  const std::string base_frame = optionalString(context, "base_frame_id", "base_link");
  const std::string odom_frame = optionalString(context, "odom_frame_id", "odom");

  left_wheels_ = getJointHandles(*hw, left, context, "left_wheel");
  right_wheels_ = getJointHandles(*hw, right, context, "right_wheel");

  if (context.topics != nullptr) {
    const std::string topic = controllerTopic(context, "cmd_vel");
    command_input_ = context.topics->commandInput<servoloop::geometry_msgs::Twist>(topic);
    auto logged = std::make_shared<std::atomic<bool>>(false);
    command_checker_ = context.topics->subscribe<servoloop::geometry_msgs::Twist>(
        topic, [topic, name = context.name, logged](const servoloop::geometry_msgs::Twist& msg) {
          if ((!std::isfinite(msg.linear.x) || !std::isfinite(msg.angular.z)) && !logged->exchange(true)) {
            logger().warn("controller '{}': ignoring non-finite command on {} (the previous command stays; "
                          "further ones are only counted)",
                          name, topic);
          }
        });
    servoloop::nav_msgs::Odometry odom;
    odom.frame_id = odom_frame;
    odom.child_frame_id = base_frame;
    for (std::size_t i = 0; i < 6; ++i) {
      odom.pose_covariance[i * 7] = pose_diagonal[i];
      odom.twist_covariance[i * 7] = twist_diagonal[i];
    }
    odom_publisher_ = context.topics->advertise<servoloop::nav_msgs::Odometry>(controllerTopic(context, "odom"), odom);
    if (publish_tf_) {
      servoloop::tf2_msgs::TFMessage tf;
      tf.transforms.resize(1);
      tf.transforms[0].frame_id = odom_frame;
      tf.transforms[0].child_frame_id = base_frame;
      tf_publisher_ = context.topics->advertise<servoloop::tf2_msgs::TFMessage>("/tf", tf);
    }
  }
  return true;
}

void DiffDriveController::brake() noexcept {
  last0_ = {};
  last1_ = {};
  for (auto& wheel : left_wheels_) wheel.setCommand(0.0);
  for (auto& wheel : right_wheels_) wheel.setCommand(0.0);
}

void DiffDriveController::starting(const Time& time) {
  brake();
  command_ = Command{0.0, 0.0, time.seconds};
  timeout_.disarm();  // standing still is no timeout
  command_input_.clear();
  odometry_.setWheelParams(separation_multiplier_ * wheel_separation_, left_radius_multiplier_ * wheel_radius_,
                           right_radius_multiplier_ * wheel_radius_);
  odometry_.reset(mean(left_wheels_), mean(right_wheels_), time.seconds);
  publish_gate_.reset();
}

void DiffDriveController::stopping(const Time& /*time*/) { brake(); }

ReturnType DiffDriveController::update(const Time& time, const Duration& period) {
  const double separation = separation_multiplier_ * wheel_separation_;
  const double left_radius = left_radius_multiplier_ * wheel_radius_;
  const double right_radius = right_radius_multiplier_ * wheel_radius_;
  odometry_.setWheelParams(separation, left_radius, right_radius);
  if (open_loop_) {
    odometry_.updateOpenLoop(last0_.linear, last0_.angular, time.seconds);
  } else {
    const double left = mean(left_wheels_);
    const double right = mean(right_wheels_);
    if (std::isfinite(left) && std::isfinite(right)) odometry_.update(left, right, time.seconds);
  }
  if (publish_gate_.due(time, period)) publishOdometry(time);

  if (command_input_.hasNewMessage()) [[unlikely]] {
    if (const servoloop::geometry_msgs::Twist* msg = command_input_.latest()) {
      if (std::isfinite(msg->linear.x) && std::isfinite(msg->angular.z)) {
        command_ = Command{msg->linear.x, msg->angular.z, time.seconds};
        timeout_.restart(time);
      } else {
        rejected_->fetch_add(1, std::memory_order_relaxed);
      }
    }
  }
  Command command = command_;
  if (time.seconds - command.stamp > cmd_vel_timeout_) {
    command.linear = command.angular = 0.0;
    timeout_.expired(time);  // reports the first cycle of each timeout
  }
  linear_limiter_.limit(command.linear, last0_.linear, last1_.linear, period.seconds);
  angular_limiter_.limit(command.angular, last0_.angular, last1_.angular, period.seconds);
  last1_ = last0_;
  last0_ = command;

  const double left_speed = (command.linear - command.angular * separation / 2.0) / left_radius;
  const double right_speed = (command.linear + command.angular * separation / 2.0) / right_radius;
  for (auto& wheel : left_wheels_) wheel.setCommand(left_speed);
  for (auto& wheel : right_wheels_) wheel.setCommand(right_speed);
  return ReturnType::ok;
}

void DiffDriveController::publishOdometry(const Time& time) noexcept {
  const double half = 0.5 * odometry_.heading();
  const servoloop::geometry_msgs::Quaternion orientation{0.0, 0.0, std::sin(half), std::cos(half)};
  if (odom_publisher_.valid() && odom_publisher_.trylock()) {
    servoloop::nav_msgs::Odometry& msg = odom_publisher_.msg();
    msg.stamp = time.seconds;
    msg.position = {odometry_.x(), odometry_.y(), 0.0};
    msg.orientation = orientation;
    msg.linear = {odometry_.linear(), 0.0, 0.0};
    msg.angular = {0.0, 0.0, odometry_.angular()};
    odom_publisher_.unlockAndPublish();
  }
  if (publish_tf_ && tf_publisher_.valid() && tf_publisher_.trylock()) {
    servoloop::geometry_msgs::TransformStamped& transform = tf_publisher_.msg().transforms[0];
    transform.stamp = time.seconds;
    transform.translation = {odometry_.x(), odometry_.y(), 0.0};
    transform.rotation = orientation;
    tf_publisher_.unlockAndPublish();
  }
}

}  // namespace servoloop::controllers::diff_drive_controller

SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::diff_drive_controller::DiffDriveController,
                          servoloop::controller_manager::ControllerBase, "diff_drive_controller/DiffDriveController")
