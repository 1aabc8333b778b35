// servoloop_ros1_bridge: a running servoloop node seen from ROS 1. Started by
// `servoloop ros1-bridge [-N NS]` (see docs/ros1.md). It is a client of the
// node's IPC socket, so whatever happens on the ROS side (no master, a slow
// subscriber, a crashing client) never reaches the node's control loop.
#include <csignal>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

#include <CLI/CLI.hpp>
#include <ros/callback_queue.h>
#include <ros/ros.h>

#include "action_bridge.hpp"
#include "controller_manager_services.hpp"
#include "gazebo_model_services.hpp"
#include "gazebo_services.hpp"
#include "robot_state_cache.hpp"
#include "node_link.hpp"
#include "parameter_bridge.hpp"
#include "pid_reconfigure.hpp"
#include "python_messages.hpp"
#include "topic_bridge.hpp"

namespace {

std::atomic<bool> g_stop{false};

void requestStop(int) { g_stop.store(true); }

// Waits for the ROS master, saying once where it looks. False when stopped;
// throws when the node ends meanwhile.
bool waitForMaster(servoloop::ros1::NodeLink& link) {
  bool said = false;
  while (!g_stop.load()) {
    if (ros::master::check()) return true;
    link.call("ping");  // the node still runs
    if (!said) {
      std::cerr << "servoloop ros1-bridge: waiting for the ROS master at " << ros::master::getURI()
                << " (start roscore, or set ROS_MASTER_URI)\n";
      said = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  return false;
}

// The ROS tools of this user find servoloop's generated message packages
// (python_messages.hpp); said once, when first set up.
void registerMessagesForRosTools() {
  std::error_code error;
  const auto registration = servoloop::ros1::registerPythonMessages(std::filesystem::read_symlink("/proc/self/exe", error));
  if (registration.written) {
    std::cout << "servoloop ros1-bridge: rostopic, rosservice and rosbag read control_msgs, controller_manager_msgs "
                 "and gazebo_msgs from "
              << registration.folder.string() << " (named in " << registration.pth.string() << ")" << std::endl;
  } else if (!registration.registered) {
    std::cerr << "servoloop ros1-bridge: " << registration.why_not
              << "; for rostopic and rosservice to read control_msgs and controller_manager_msgs, run: "
                 "eval \"$(servoloop ros1-bridge --print-env)\"\n";
  }
}

int runBridge(const std::string& requested_namespace, bool use_sim_time, bool gazebo_services) {
  registerMessagesForRosTools();
  const std::string node_namespace = servoloop::ros1::pickNodeNamespace(requested_namespace);
  servoloop::ros1::NodeLink link(node_namespace);

  if (!waitForMaster(link)) return 0;
  ros::NodeHandle nh;
  const servoloop::ros1::ParameterCopy copy = servoloop::ros1::copyParametersToRos(link, use_sim_time);
  // The services on a connection of their own: a switch that takes a while
  // never holds up the commands flowing from ROS on `link`.
  servoloop::ros1::NodeLink service_link(node_namespace);
  std::optional<servoloop::ros1::ControllerManagerServices> services;
  services.emplace(nh, service_link, copy.copied);
  servoloop::ros1::RobotStateCache robot_state;
  std::optional<servoloop::ros1::TopicBridge> topics;
  topics.emplace(nh, link, robot_state);
  // Gazebo's joint, world and model services, on a connection of their own.
  std::optional<servoloop::ros1::NodeLink> gazebo_link;
  std::optional<servoloop::ros1::GazeboServices> gazebo;
  std::optional<servoloop::ros1::GazeboModelServices> gazebo_models;
  if (gazebo_services) {
    gazebo_link.emplace(node_namespace);
    gazebo.emplace(nh, *gazebo_link, robot_state);
    gazebo_models.emplace(nh, *gazebo_link, robot_state);
  }
  // Actions on a connection of their own (the node answers a goal's status
  // only on the connection that sent it), polled on a thread of their own.
  servoloop::ros1::NodeLink action_link(node_namespace);
  std::optional<servoloop::ros1::ActionBridge> actions;
  actions.emplace(nh, action_link);
  // The PIDs' dynamic_reconfigure, on a connection of its own.
  servoloop::ros1::NodeLink pid_link(node_namespace);
  std::optional<servoloop::ros1::PidReconfigureServers> pids;
  pids.emplace(nh, pid_link);
  // Service calls (a switch, a goal being sent, a first joint state awaited)
  // may take a while: enough threads that commands still flow meanwhile.
  ros::AsyncSpinner spinner(4);
  spinner.start();
  std::thread action_thread([&] {
    // A failed request (a timeout, say) is reported at most once a second and
    // tried again; the node ending is noticed by the topic thread.
    auto next_discovery = std::chrono::steady_clock::now();
    auto next_report = std::chrono::steady_clock::now();
    while (!g_stop.load() && ros::ok()) {
      try {
        if (std::chrono::steady_clock::now() >= next_discovery) {
          next_discovery += std::chrono::seconds(1);
          actions->discover();
          pids->discover();
        }
        actions->poll();
      } catch (const std::exception& e) {
        if (std::chrono::steady_clock::now() >= next_report) {
          std::cerr << "servoloop ros1-bridge: actions: " << e.what() << "\n";
          next_report = std::chrono::steady_clock::now() + std::chrono::seconds(1);
        }
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });
  std::cout << "servoloop ros1-bridge: bridging " << node_namespace << " to the ROS master at "
            << ros::master::getURI() << " (" << copy.parameters << " parameters"
            << (copy.robot_description ? ", robot_description" : "") << ", /clock, "
            << link.resolve("controller_manager") << "/*, the PIDs' dynamic_reconfigure"
            << (gazebo_services ? ", /gazebo/*" : "") << ")" << std::endl;
  std::string failure;
  try {
    topics->run(g_stop);
  } catch (const std::exception& e) {
    failure = e.what();
  }
  g_stop.store(true);
  action_thread.join();
  // The spinner's threads wait on the callback queue: woken at once.
  ros::getGlobalCallbackQueue()->disable();
  spinner.stop();
  // Each topic and service is one call to the master to take it down: the
  // parts go side by side, so that Ctrl-C ends the bridge within half a
  // second.
  std::thread services_down([&] { services.reset(); });
  std::thread gazebo_down([&] {
    gazebo_models.reset();
    gazebo.reset();
  });
  std::thread actions_down([&] {
    actions.reset();
    pids.reset();
  });
  topics.reset();
  services_down.join();
  gazebo_down.join();
  actions_down.join();
  ros::shutdown();
  if (!failure.empty()) throw std::runtime_error(failure + "; the bridge stops");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"servoloop_ros1_bridge: a running servoloop node's topics, parameters and controller manager in ROS 1"};
  std::string requested_namespace;
  bool no_sim_time = false;
  app.add_option("-N,--namespace", requested_namespace,
                 "Robot namespace of the node to bridge, e.g. /one_DOF_robot (default: the only running node)")
      ->type_name("NS");
  app.add_flag("--no-sim-time", no_sim_time, "Leave /use_sim_time false (ROS nodes keep the wall clock)");
  bool no_gazebo_services = false;
  app.add_flag("--no-gazebo-services", no_gazebo_services,
               "Do not serve Gazebo's services: /gazebo/get_joint_properties, apply_joint_effort, get_model_state, "
               "set_model_state, set_model_configuration, spawn_urdf_model, delete_model, pause_physics, "
               "unpause_physics, reset_simulation, reset_world");
  // ROS remappings (name:=value) pass through to ros::init.
  app.allow_extras();
  CLI11_PARSE(app, argc, argv);

  std::signal(SIGINT, requestStop);
  std::signal(SIGTERM, requestStop);
  try {
    const std::string ros_name = "servoloop_bridge" + (requested_namespace.empty() ? std::string() :
        "_" + servoloop::ros1::namespaceStem(requested_namespace));
    ros::init(argc, argv, ros_name, ros::init_options::NoSigintHandler);
    return runBridge(requested_namespace, !no_sim_time, !no_gazebo_services);
  } catch (const std::exception& e) {
    std::cerr << "servoloop ros1-bridge: " << e.what() << "\n";
    return 1;
  }
}
