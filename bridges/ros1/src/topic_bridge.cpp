#include "topic_bridge.hpp"

#include <chrono>
#include <atomic>
#include <cmath>
#include <memory>
#include <set>
#include <vector>

#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>


namespace servoloop::ros1 {

using nlohmann::json;
using SteadyClock = std::chrono::steady_clock;

TopicBridge::TopicBridge(ros::NodeHandle& nh, NodeLink& link, RobotStateCache& state, TopicBridgeOptions options)
    : nh_(nh),
      link_(link),
      state_(state),
      options_(options),
      streams_(link.nodeNamespace()),
      joint_states_topic_(link.resolve("joint_states")),
      ground_truth_topic_(link.resolve("ground_truth/odom")),
      clock_(nh.advertise<rosgraph_msgs::Clock>("/clock", 10)) {}

void TopicBridge::discover() {
  const json topics = streams_.call("topic.list").at("topics");
  std::set<std::string> listed;
  for (const json& topic : topics) {
    const std::string name = topic.at("name").get<std::string>();
    const std::string type_name = topic.value("type", "");
    listed.insert(name);
    if (skipped_.count(name) != 0 || type_name.empty()) continue;
    const BridgedType* type = findBridgedType(type_name);
    // The node's own end of the topic: its publishers for a topic going to
    // ROS, its subscribers (a controller's command input) for one coming from it.
    const std::size_t endpoints =
        topic.value(type != nullptr && type->command ? "subscribers" : "publishers", std::size_t{0});
    if (directions_.count(name) != 0) {
      if (endpoints > 0) {
        had_endpoint_.insert(name);
      } else if (had_endpoint_.count(name) != 0) {
        retire(name);
      }
      continue;
    }
    if (retired_.count(name) != 0) {
      if (endpoints == 0) continue;
      retired_.erase(name);
    }
    if (type == nullptr) {
      ROS_WARN("servoloop bridge: topic %s has type %s, which the bridge does not carry; it stays in servoloop",
               name.c_str(), type_name.c_str());
      skipped_.insert(name);
      continue;
    }
    try {
      bridgeTopic(name, type_name, *type);
    } catch (const ros::InvalidNameException& e) {
      // servoloop's names allow what ROS's do not (a '-', a leading digit).
      ROS_WARN("servoloop bridge: topic %s stays in servoloop: ROS does not accept its name (%s)", name.c_str(), e.what());
      skipped_.insert(name);
      continue;
    }
    if (endpoints > 0) had_endpoint_.insert(name);
    ROS_INFO("servoloop bridge: %s (%s) %s", name.c_str(), type_name.c_str(), directions_.at(name).c_str());
  }
  // A topic the node no longer lists at all goes too.
  std::vector<std::string> gone;
  for (const auto& [name, direction] : directions_) {
    if (listed.count(name) == 0) gone.push_back(name);
  }
  for (const std::string& name : gone) retire(name);
}

void TopicBridge::retire(const std::string& name) {
  const auto direction = directions_.find(name);
  if (direction == directions_.end()) return;
  if (direction->second == "to ROS") {
    to_ros_.erase(name);  // its ROS publisher with it: unadvertised
    try {
      streams_.call("topic.unsubscribe", {{"topic", name}});
    } catch (const std::exception& e) {
      ROS_WARN("servoloop bridge: %s: the node's stream stays open: %s", name.c_str(), e.what());
    }
  } else {
    from_ros_.erase(name);  // its ROS subscriber with it: unsubscribed
  }
  ROS_INFO("servoloop bridge: %s taken off the master (nothing in the node %s it any more)", name.c_str(),
           direction->second == "to ROS" ? "publishes" : "subscribes to");
  directions_.erase(direction);
  had_endpoint_.erase(name);
  retired_.insert(name);
}

void TopicBridge::bridgeTopic(const std::string& name, const std::string& type_name, const BridgedType& type) {
  if (type.command) {
    // The ROS message goes to the node's bus; a refusal (a NaN command, say)
    // is the node's one-line error, reported (at most once a second per
    // topic) without stopping the bridge.
    auto last_warning = std::make_shared<std::atomic<double>>(-1.0);
    from_ros_.emplace(name, type.subscribe(nh_, name, [this, name, type_name, last_warning](json msg) {
      try {
        link_.call("topic.pub", {{"topic", name}, {"type", type_name}, {"msg", std::move(msg)}});
      } catch (const std::exception& e) {
        const double now = ros::WallTime::now().toSec();
        double last = last_warning->load();
        if (now - last >= 1.0 && last_warning->compare_exchange_strong(last, now)) {
          ROS_WARN("servoloop bridge: %s not delivered: %s", name.c_str(), e.what());
        }
      }
    }));
    directions_.emplace(name, "from ROS");
  } else {
    to_ros_.emplace(name, type.advertise(nh_, name));
    streams_.call("topic.subscribe", {{"topic", name}});
    directions_.emplace(name, "to ROS");
  }
}

void TopicBridge::forwardToRos(const json& stream_message) {
  const std::string topic = stream_message.value("stream", "");
  const auto it = to_ros_.find(topic);
  if (it == to_ros_.end()) return;
  const json& msg = stream_message.at("msg");
  if (topic == joint_states_topic_) state_.updateJoints(msg);
  if (topic == ground_truth_topic_) state_.updateGroundTruth(msg);
  try {
    it->second(msg);
  } catch (const std::exception& e) {
    if (conversion_warned_.insert(topic).second) {
      ROS_WARN("servoloop bridge: messages on %s not converted: %s (said once)", topic.c_str(), e.what());
    }
  }
  if (const auto stamp = stream_message.find("stamp"); stamp != stream_message.end() && stamp->is_number()) {
    publishClock(stamp->get<double>());
  }
}

void TopicBridge::publishClock(double sim_time) {
  if (!(sim_time > last_clock_) || !std::isfinite(sim_time)) return;
  rosgraph_msgs::Clock clock;
  clock.clock = ros::Time(sim_time);
  clock_.publish(clock);
  last_clock_ = sim_time;
  state_.updateSimTime(sim_time);
}

void TopicBridge::run(const std::atomic<bool>& stop) {
  const auto discovery_period = std::chrono::duration<double>(options_.discovery_period_s);
  const auto clock_period = std::chrono::duration<double>(options_.clock_period_s);
  SteadyClock::time_point next_discovery = SteadyClock::now();
  SteadyClock::time_point next_clock = SteadyClock::now();
  while (!stop.load() && ros::ok()) {
    const SteadyClock::time_point now = SteadyClock::now();
    if (now >= next_discovery) {
      discover();
      next_discovery = now + std::chrono::duration_cast<SteadyClock::duration>(discovery_period);
    }
    if (now >= next_clock) {
      publishClock(streams_.call("ping").value("sim_time", 0.0));
      next_clock = now + std::chrono::duration_cast<SteadyClock::duration>(clock_period);
    }
    const double wait_s = std::chrono::duration<double>(std::min(next_discovery, next_clock) - SteadyClock::now()).count();
    if (auto message = streams_.readStream(std::max(wait_s, 0.0005))) forwardToRos(*message);
    // Drain what else arrived without waiting.
    while (auto more = streams_.readStream(0.0)) forwardToRos(*more);
  }
}

}  // namespace servoloop::ros1
