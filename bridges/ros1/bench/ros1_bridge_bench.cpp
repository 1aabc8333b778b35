// servoloop_bench_ros1_bridge: what the ROS 1 bridge costs, measured on a
// running node with the bridge and a ROS master up (scripts/bench_ros1.sh runs
// it; figures in docs/benchmarks.md).
//
//   --mode ros-latency   commands published by a ROS node (roscpp, as rostopic
//                        pub does) until the node's bus has them: each command
//                        is timed from its publication to its arrival on an IPC
//                        subscription of the same topic in the node.
//   --mode ipc-latency   the same commands sent over the node's socket
//                        (topic.pub, as `servoloop topic pub` does): the
//                        reference for the leg both paths share.
//   --mode delivery      a ROS subscriber of a state topic for --seconds wall
//                        seconds: messages received, and from their stamps the
//                        messages missing or repeated.
// Times are wall (steady) clock; both ends are in this process.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>

#include "node_link.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  const auto index = static_cast<std::size_t>(std::ceil(p / 100.0 * static_cast<double>(values.size())) - 1);
  return values[std::min(index, values.size() - 1)];
}

// Commands 1.0 + i·1e-6 rad (distinct, all within the seed joint's limits),
// sent at `rate_hz`; returns the latencies (seconds) of those that arrived.
int runLatency(const std::string& ns, const std::string& topic, int count, double rate_hz, bool through_ros) {
  servoloop::ros1::NodeLink streams(ns);
  servoloop::ros1::NodeLink requests(ns);
  streams.call("topic.subscribe", {{"topic", topic}});
  std::unique_ptr<ros::NodeHandle> nh;
  ros::Publisher publisher;
  if (through_ros) {
    nh = std::make_unique<ros::NodeHandle>();
    publisher = nh->advertise<std_msgs::Float64>(topic, 1000);
    const auto deadline = Clock::now() + std::chrono::seconds(10);
    while (publisher.getNumSubscribers() == 0 && Clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (publisher.getNumSubscribers() == 0) {
      std::fprintf(stderr, "no subscriber of %s in ROS: is `servoloop ros1-bridge` running?\n", topic.c_str());
      return 1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the connection settles
  }
  std::vector<Clock::time_point> sent(count);
  std::vector<double> latency(count, -1.0);
  std::atomic<bool> done{false};
  std::thread reader([&] {
    while (!done.load()) {
      const auto message = streams.readStream(0.05);
      if (!message) continue;
      const auto now = Clock::now();
      const double data = message->value("msg", nlohmann::json::object()).value("data", 0.0);
      const long index = std::lround((data - 1.0) * 1e6);
      if (index >= 0 && index < count && latency[index] < 0.0) {
        latency[index] = std::chrono::duration<double>(now - sent[index]).count();
      }
    }
  });
  const auto period = std::chrono::duration<double>(1.0 / rate_hz);
  auto next = Clock::now();
  for (int i = 0; i < count; ++i) {
    std::this_thread::sleep_until(next);
    next += std::chrono::duration_cast<Clock::duration>(period);
    const double value = 1.0 + static_cast<double>(i) * 1e-6;
    sent[i] = Clock::now();
    if (through_ros) {
      std_msgs::Float64 msg;
      msg.data = value;
      publisher.publish(msg);
    } else {
      requests.call("topic.pub", {{"topic", topic}, {"type", "std_msgs/Float64"}, {"msg", {{"data", value}}}});
    }
  }
  std::this_thread::sleep_for(std::chrono::seconds(1));
  done.store(true);
  reader.join();
  std::vector<double> arrived;
  for (double l : latency) {
    if (l >= 0.0) arrived.push_back(l * 1e3);
  }
  std::printf("%s command latency: %zu of %d arrived; p50 %.3f ms, p99 %.3f ms, max %.3f ms\n",
              through_ros ? "ros" : "ipc", arrived.size(), count, percentile(arrived, 50), percentile(arrived, 99),
              arrived.empty() ? std::nan("") : *std::max_element(arrived.begin(), arrived.end()));
  return 0;
}

int runDelivery(const std::string& topic, double seconds, double expected_period_s) {
  ros::NodeHandle nh;
  std::mutex mutex;
  std::vector<std::int64_t> stamps_ns;
  const ros::Subscriber subscriber = nh.subscribe<sensor_msgs::JointState>(
      topic, 10000, [&](const sensor_msgs::JointState::ConstPtr& msg) {
        std::lock_guard lock(mutex);
        stamps_ns.push_back(static_cast<std::int64_t>(msg->header.stamp.toNSec()));
      });
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const auto deadline = Clock::now() + std::chrono::duration<double>(seconds);
  while (Clock::now() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  spinner.stop();
  std::lock_guard lock(mutex);
  if (stamps_ns.size() < 2) {
    std::fprintf(stderr, "fewer than two messages on %s in %.1f s\n", topic.c_str(), seconds);
    return 1;
  }
  const auto period_ns = static_cast<std::int64_t>(std::llround(expected_period_s * 1e9));
  std::int64_t missing = 0;
  std::int64_t repeated = 0;
  for (std::size_t i = 1; i < stamps_ns.size(); ++i) {
    const std::int64_t step = stamps_ns[i] - stamps_ns[i - 1];
    if (step <= 0) {
      ++repeated;
    } else if (step > period_ns) {
      missing += (step + period_ns / 2) / period_ns - 1;
    }
  }
  const double span_s = static_cast<double>(stamps_ns.back() - stamps_ns.front()) * 1e-9;
  std::printf("delivery of %s at %.0f Hz: %zu messages over %.3f s of simulated time (%.1f per wall second); "
              "missing %lld, repeated %lld\n",
              topic.c_str(), 1.0 / expected_period_s, stamps_ns.size(), span_s,
              static_cast<double>(stamps_ns.size()) / seconds, static_cast<long long>(missing),
              static_cast<long long>(repeated));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"servoloop_bench_ros1_bridge: the ROS 1 bridge's command latency and state delivery"};
  std::string mode;
  std::string ns = "/one_DOF_robot";
  std::string topic;
  int count = 1000;
  double rate_hz = 100.0;
  double seconds = 10.0;
  double period_s = 0.02;
  app.add_option("--mode", mode, "ros-latency, ipc-latency or delivery")->required();
  app.add_option("-N,--namespace", ns, "The node's robot namespace");
  app.add_option("--topic", topic, "Command topic (latency) or JointState topic (delivery)")->required();
  app.add_option("--count", count, "Commands to send (latency)");
  app.add_option("--rate", rate_hz, "Commands per second (latency)");
  app.add_option("--seconds", seconds, "Wall seconds to listen (delivery)");
  app.add_option("--period", period_s, "The topic's publishing period in simulated seconds (delivery)");
  CLI11_PARSE(app, argc, argv);
  ros::init(argc, argv, "servoloop_bench_ros1_bridge", ros::init_options::AnonymousName);
  try {
    if (mode == "ros-latency") return runLatency(ns, topic, count, rate_hz, true);
    if (mode == "ipc-latency") return runLatency(ns, topic, count, rate_hz, false);
    if (mode == "delivery") return runDelivery(topic, seconds, period_s);
    std::fprintf(stderr, "--mode %s: use ros-latency, ipc-latency or delivery\n", mode.c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "servoloop_bench_ros1_bridge: %s\n", e.what());
    return 1;
  }
}
