#include "compare_run.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>

#include <urdf_model/model.h>

#include "servoloop/realtime/messages.hpp"
#include "servoloop/node/node.hpp"
#include "servoloop/plugin/plugin_loader.hpp"
#include "servoloop/plugin/plugin_path.hpp"
#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::cli {
namespace {

namespace node = servoloop::node;
using nlohmann::json;

// The messages of one topic, filled on the robot's delivery thread (or the
// thread flushing its bus) and read once the run is over.
struct TopicCapture {
  std::mutex mutex;
  JointTrajectory trajectory;
  bool not_joint_states = false;  // a message without name/position arrays came
};

std::vector<double> numbers(const json& values) {
  std::vector<double> out;
  if (!values.is_array()) return out;
  out.reserve(values.size());
  for (const json& value : values) {
    // message_json writes non-finite numbers as null.
    out.push_back(value.is_number() ? value.get<double>() : std::numeric_limits<double>::quiet_NaN());
  }
  return out;
}

void addMessage(TopicCapture& capture, Time stamp, const json& msg) {
  std::lock_guard lock(capture.mutex);
  if (!msg.is_object() || !msg.contains("name") || !msg["name"].is_array() || !msg.contains("position")) {
    capture.not_joint_states = true;
    return;
  }
  std::vector<std::string> names;
  for (const json& name : msg["name"]) names.push_back(name.is_string() ? name.get<std::string>() : "");
  capture.trajectory.append(stamp.seconds, names, numbers(msg["position"]), numbers(msg.value("velocity", json())));
}

// The robot whose namespace is the longest prefix of `topic`.
node::RobotInstance* robotOwning(node::Node& world, const std::string& topic) {
  node::RobotInstance* owner = nullptr;
  std::size_t longest = 0;
  for (node::RobotInstance* robot : world.robots()) {
    const std::string& ns = robot->robotNamespace();
    const bool under = ns == "/" || (topic.size() > ns.size() && topic.compare(0, ns.size(), ns) == 0 &&
                                     topic[ns.size()] == '/');
    if (under && ns.size() >= longest) {
      owner = robot;
      longest = ns.size();
    }
  }
  return owner;
}

std::string joinedNamespaces(node::Node& world) {
  std::string names;
  for (const std::string& ns : world.robotNamespaces()) names += (names.empty() ? "" : ", ") + ns;
  return names.empty() ? "none" : names;
}

}  // namespace

std::vector<std::string> availableBackends(const std::vector<std::filesystem::path>& plugin_directories) {
  servoloop::plugin::PluginLoader loader(servoloop::plugin::pluginSearchPath(plugin_directories));
  std::vector<std::string> names;
  for (const servoloop::plugin::PluginTypeInfo& info : loader.listTypes(hardware_interface::RobotHW::kPluginKind)) {
    names.push_back(info.type);
  }
  std::sort(names.begin(), names.end());
  return names;
}

void requireBackend(const std::string& backend, const std::vector<std::string>& available) {
  if (std::find(available.begin(), available.end(), backend) != available.end()) return;
  std::string names;
  for (const std::string& name : available) names += (names.empty() ? "" : ", ") + name;
  if (names.empty()) names = "none (is the plugin folder on SERVOLOOP_PLUGIN_PATH or given with --plugin-dir?)";
  if (backend == "mujoco") {
    throw Error("backend 'mujoco' is not available: this servoloop was built without MuJoCo (install "
                "libmujoco-dev and rebuild) or its plugin is not on the plugin path; available backends: " +
                names);
  }
  throw Error("unknown backend '" + backend + "'; available backends: " + names);
}

BackendRun runOnBackend(const BackendRunRequest& request) {
  node::LaunchFile launch = request.launch;
  launch.record.clear();
  launch.plot.clear();
  node::NodeOptions options;
  options.duration_s = request.duration_s;
  options.real_time_factor = 0.0;  // free-running: the comparison is in simulated time
  options.backend = request.backend;
  options.serve_ipc = false;
  options.plugin_directories = request.plugin_directories;

  // Declared before the node: the callbacks point into them.
  std::vector<std::unique_ptr<TopicCapture>> captures;
  std::vector<servoloop::realtime::Subscription> subscriptions;
  node::Node world(std::move(launch), options);

  std::vector<std::string> topics = request.topics;
  if (topics.empty()) {
    for (const std::string& ns : world.robotNamespaces()) topics.push_back((ns == "/" ? "" : ns) + "/joint_states");
    if (topics.empty()) throw Error("the launch file spawns no robot, so there is nothing to compare");
  }
  std::vector<node::RobotInstance*> owners;
  for (const std::string& topic : topics) {
    node::RobotInstance* robot = robotOwning(world, topic);
    if (robot == nullptr) {
      throw Error("--topic " + topic + ": no robot's namespace contains it (robots: " + joinedNamespaces(world) +
                  ")");
    }
    owners.push_back(robot);
    captures.push_back(std::make_unique<TopicCapture>());
    captures.back()->trajectory.topic = topic;
    TopicCapture* capture = captures.back().get();
    subscriptions.push_back(servoloop::node::subscribeJson(
        robot->topics(), topic, [capture](Time stamp, const json& msg) { addMessage(*capture, stamp, msg); }));
  }

  // The URDFs, for the joints' units once the robots are gone.
  std::vector<std::shared_ptr<const urdf::ModelInterface>> models;
  std::vector<std::string> topic_types;
  world.start();
  world.waitUntilDone();
  for (std::size_t k = 0; k < topics.size(); ++k) {
    models.push_back(owners[k]->model());
    const bool known = owners[k]->topics().hasTopic(topics[k]);
    topic_types.push_back(known ? owners[k]->topics().typeOf(topics[k]) : std::string());
  }
  world.shutdown();  // delivers what is still queued
  subscriptions.clear();

  BackendRun run;
  run.backend = request.backend;
  run.summary = world.summary();
  for (std::size_t k = 0; k < topics.size(); ++k) {
    std::lock_guard lock(captures[k]->mutex);
    if (!topic_types[k].empty() && topic_types[k] != servoloop::sensor_msgs::JointState::kTypeName) {
      throw Error("topic '" + topics[k] + "' carries " + topic_types[k] +
                  "; compare reads sensor_msgs/JointState topics (e.g. <namespace>/joint_states)");
    }
    JointTrajectory trajectory = std::move(captures[k]->trajectory);
    trajectory.sortByStamp();
    if (captures[k]->not_joint_states) {
      throw Error("topic '" + topics[k] + "' carries messages that are not sensor_msgs/JointState; compare reads "
                  "joint states (e.g. <namespace>/joint_states)");
    }
    if (trajectory.samples() == 0) {
      throw Error("topic '" + topics[k] + "': nothing was recorded on backend '" + request.backend +
                  "' in " + std::to_string(request.duration_s) +
                  " s; does the robot run a joint_state_controller publishing there?");
    }
    for (std::size_t j = 0; j < trajectory.joints.size(); ++j) {
      const auto joint = models[k] ? models[k]->getJoint(trajectory.joints[j]) : nullptr;
      trajectory.units[j] = (joint && joint->type == urdf::Joint::PRISMATIC) ? "m" : "rad";
    }
    run.trajectories.push_back(std::move(trajectory));
  }
  return run;
}

}  // namespace servoloop::cli
