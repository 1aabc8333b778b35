#include "python_world.hpp"

#include <cmath>
#include <filesystem>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/node/launch_file.hpp"
#include "servoloop/node/message_json.hpp"
#include "servoloop/node/node_operations.hpp"

namespace servoloop::python {
namespace {

// Messages one subscription keeps between two calls; older ones are dropped.
constexpr std::size_t kMaxInboxMessages = 1'000'000;

}  // namespace

World::Busy::Busy(std::atomic<bool>& busy) : busy_(busy) {
  if (busy_.exchange(true)) {
    throw Error("this World is in use by another thread (step, reset, set_param or close); use one World per thread");
  }
}

World::World(const std::string& launch_file, const WorldOptions& options) {
  setLogLevel(options.log_level);
  node::NodeOptions node_options;
  node_options.serve_ipc = false;
  node_options.real_time_factor = 0.0;
  node_options.start_paused = true;
  node_options.backend = options.backend;
  for (const auto& [name, value] : options.params) {
    YAML::Node parsed;
    try {
      parsed = YAML::Load(value);
    } catch (const YAML::Exception& e) {
      throw ConfigError(fmt::format("params: the value of '{}' is not a number, list or map: {}", name, e.what()));
    }
    node_options.parameter_overrides.emplace_back(name, parsed);
  }
  node_ = std::make_unique<node::Node>(node::loadLaunchFile(std::filesystem::absolute(launch_file)), node_options);
  time_step_s_ = node_->launchFile().world.time_step_s;
  node_->start();
}

World::~World() {
  try {
    close();
  } catch (const std::exception& e) {
    logger().error("closing the world failed: {}", e.what());
  }
}

node::Node& World::node() const {
  if (!node_) throw Error("this World is closed");
  return *node_;
}

void World::close() {
  if (!node_) return;
  const Busy busy(busy_);
  inboxes_.clear();
  node_->shutdown();
  node_.reset();
}

void World::reset() {
  const Busy busy(busy_);
  const std::string failures = node().resetWorld(changed_parameters_);
  changed_parameters_.clear();
  flushBuses();
  if (!failures.empty()) throw Error("reset: " + failures);
}

std::uint64_t World::step(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0 || seconds > 1e9) {
    throw Error(fmt::format("step: {} s must be a time from 0 to 1e9 s", seconds));
  }
  // A tolerance of 1e-9 steps absorbs rounding: 1.0 s at 0.001 s is 1000 steps.
  const auto cycles = static_cast<std::uint64_t>(std::ceil(seconds / time_step_s_ - 1e-9));
  return stepCycles(cycles);
}

std::uint64_t World::stepCycles(std::uint64_t cycles) {
  if (cycles > 1'000'000'000'000ULL) throw Error(fmt::format("step_cycles: {} steps is more than 1e12", cycles));
  const Busy busy(busy_);
  const std::uint64_t ran = cycles == 0 ? 0 : node().stepWorld(cycles);
  flushBuses();
  return ran;
}

double World::time() const { return node().simTime(); }
double World::timeStep() const { return time_step_s_; }

std::vector<std::string> World::namespaces() const { return node().robotNamespaces(); }

std::map<std::string, std::string> World::topics() const {
  std::map<std::string, std::string> topics;
  for (node::RobotInstance* robot : node().robots()) {
    for (const realtime::TopicInfo& topic : robot->topics().list()) topics[topic.name] = topic.type;
  }
  return topics;
}

void World::flushBuses() const {
  for (node::RobotInstance* robot : node().robots()) robot->topics().flush();
}

node::RobotInstance& World::robotFor(const std::string& robot_namespace) const {
  if (robot_namespace.empty()) {
    const std::vector<node::RobotInstance*> robots = node().robots();
    if (robots.size() == 1) return *robots.front();
    throw Error(robots.empty() ? std::string("this world has no robot")
                               : fmt::format("this world has several robots ({}); name one", robotNames()));
  }
  node::RobotInstance* robot = node().findModel(robot_namespace);
  if (robot == nullptr) {
    throw Error(fmt::format("no robot or model '{}' in this world (it has: {})", robot_namespace, robotNames()));
  }
  return *robot;
}

std::string World::robotNames() const {
  std::string names;
  for (const std::string& ns : node().robotNamespaces()) names += (names.empty() ? "" : ", ") + ns;
  return names;
}

node::RobotInstance& World::robotForTopic(const std::string& topic) const {
  node::RobotInstance* robot = node().robotForTopic(topic);
  if (robot == nullptr) throw Error(fmt::format("'{}': this world has no robot to carry the topic", topic));
  return *robot;
}

void World::publish(const std::string& topic, const nlohmann::json& value, const std::string& type) {
  const std::string name = realtime::TopicBus::normalizeTopicName(topic);
  realtime::TopicBus& bus = robotForTopic(name).topics();
  node::TimedPublication publication = node::makeTimedPublication(name, type, value, 0.0, "publish");
  publication = node::withTopicType(publication, bus.hasTopic(name) ? bus.typeOf(name) : "");
  node::publishJson(bus, name, publication.message, publication.type);
  bus.flush();
}

nlohmann::json World::subscribe(const std::string& topic) {
  const std::string name = realtime::TopicBus::normalizeTopicName(topic);
  realtime::TopicBus& bus = robotForTopic(name).topics();
  auto found = inboxes_.find(name);
  if (found == inboxes_.end()) {
    auto inbox = std::make_unique<Inbox>();
    Inbox* target = inbox.get();
    inbox->subscription = node::subscribeJson(bus, name, [target, &bus, name](Time stamp, const nlohmann::json& msg) {
      std::lock_guard lock(target->mutex);
      if (target->messages.size() >= kMaxInboxMessages) target->messages.pop_front();
      target->messages.push_back({{"stamp", stamp.seconds}, {"type", bus.hasTopic(name) ? bus.typeOf(name) : ""},
                                  {"msg", msg}});
    });
    inboxes_.emplace(name, std::move(inbox));
    return nlohmann::json::array();
  }
  bus.flush();
  nlohmann::json messages = nlohmann::json::array();
  std::lock_guard lock(found->second->mutex);
  for (auto& message : found->second->messages) messages.push_back(std::move(message));
  found->second->messages.clear();
  return messages;
}

JointStates World::jointState(const std::string& robot_namespace) const {
  JointStates states;
  for (const node::JointReading& joint : robotFor(robot_namespace).joints()) {
    states.name.push_back(joint.name);
    states.position.push_back(joint.position);
    states.velocity.push_back(joint.velocity);
    states.effort.push_back(joint.effort);
  }
  return states;
}

nlohmann::json World::modelState(const std::string& name) const {
  return node::modelStateToJson(node().modelState(name));
}

nlohmann::json World::setModelState(const nlohmann::json& request) {
  const Busy busy(busy_);
  return node::setModelStateFromJson(node(), request);
}

void World::setParam(const std::string& name, const std::string& value_json) {
  if (name.empty() || name == "/") throw Error("set_param: name a parameter, e.g. /robot/controller/pid/p");
  const Busy busy(busy_);
  YAML::Node value;
  try {
    value = YAML::Load(value_json);
  } catch (const YAML::Exception& e) {
    throw Error(fmt::format("set_param: the value of '{}' is not a number, string, list or map: {}", name, e.what()));
  }
  node().parameters().setNode(name, value);
  changed_parameters_.push_back(name.front() == '/' ? name : "/" + name);
}

nlohmann::json World::getParam(const std::string& name) const {
  return node::yamlToJson(node().parameters().node(name));
}

}  // namespace servoloop::python
