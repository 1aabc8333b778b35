#include "servoloop/node/ground_truth_publisher.hpp"

#include <Eigen/Geometry>

#include "servoloop/core/errors.hpp"

namespace servoloop::node {

bool GroundTruthPublisher::applies(const hardware_interface::SimulatedRobotHW& hardware) {
  hardware_interface::BaseGroundTruth probe;
  return hardware.readBaseGroundTruth(probe);
}

namespace {

nav_msgs::Odometry prototype(const std::string& root_link) {
  nav_msgs::Odometry msg;
  msg.frame_id = "world";
  msg.child_frame_id = root_link;
  return msg;
}

}  // namespace

GroundTruthPublisher::GroundTruthPublisher(const hardware_interface::SimulatedRobotHW& hardware,
                                           realtime::TopicBus& bus, const std::string& topic,
                                           const std::string& root_link, double rate_hz)
    : hardware_(hardware),
      publisher_(bus.advertise<nav_msgs::Odometry>(topic, prototype(root_link))),
      interval_s_(1.0 / rate_hz) {
  // The staging message starts as the prototype, with the frame names; each
  // cycle changes numbers only, so publishing never allocates.
  if (!(rate_hz > 0.0)) throw ConfigError("ground truth publisher: the rate must be > 0 Hz");
}

void GroundTruthPublisher::afterUpdate(const Time& time, const Duration& /*period*/) noexcept {
  if (time.seconds < next_time_s_) return;
  hardware_interface::BaseGroundTruth base;
  if (!hardware_.readBaseGroundTruth(base) || !publisher_.trylock()) return;
  next_time_s_ = time.seconds + interval_s_ - 1e-9;
  nav_msgs::Odometry& msg = publisher_.msg();
  msg.stamp = time.seconds;
  msg.position = {base.position[0], base.position[1], base.position[2]};
  msg.orientation = {base.orientation[0], base.orientation[1], base.orientation[2], base.orientation[3]};
  // ROS's Odometry gives the twist in the child frame: R^T v.
  const Eigen::Quaterniond to_world(base.orientation[3], base.orientation[0], base.orientation[1],
                                    base.orientation[2]);
  const Eigen::Vector3d linear =
      to_world.conjugate() * Eigen::Vector3d(base.linear_velocity[0], base.linear_velocity[1], base.linear_velocity[2]);
  const Eigen::Vector3d angular = to_world.conjugate() * Eigen::Vector3d(base.angular_velocity[0],
                                                                          base.angular_velocity[1],
                                                                          base.angular_velocity[2]);
  msg.linear = {linear.x(), linear.y(), linear.z()};
  msg.angular = {angular.x(), angular.y(), angular.z()};
  publisher_.unlockAndPublish();
}

}  // namespace servoloop::node
