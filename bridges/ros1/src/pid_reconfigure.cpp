#include "pid_reconfigure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>
#include <utility>
#include <vector>

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <ros/ros.h>

namespace servoloop::ros1 {

using nlohmann::json;
namespace dr = dynamic_reconfigure;

// One PID's gains as dynamic_reconfigure carries them.
struct Gains {
  std::array<double, 5> values{};  // in kDoubles' order
  bool antiwindup = false;
  bool operator==(const Gains& other) const { return values == other.values && antiwindup == other.antiwindup; }
};

namespace {

// control_toolbox's PID parameters: names, defaults and ranges as its
// dynamic_reconfigure configuration declares them (a value outside the range
// is clamped to it); antiwindup is the one boolean.
struct DoubleParameter {
  const char* name;
  const char* meaning;
  double default_value;
  double min;
  double max;
};
constexpr std::array<DoubleParameter, 5> kDoubles = {{
    {"p", "proportional gain", 10.0, -100000.0, 100000.0},
    {"i", "integral gain", 0.1, -1000.0, 1000.0},
    {"d", "derivative gain", 1.0, -1000.0, 1000.0},
    {"i_clamp_min", "lower bound of the integral term", -10.0, -1000.0, 0.0},
    {"i_clamp_max", "upper bound of the integral term", 10.0, 0.0, 1000.0},
}};
constexpr const char* kAntiwindup = "antiwindup";
constexpr const char* kGroup = "Default";  // dynamic_reconfigure's top group

Gains gainsFromJson(const json& pid) {
  Gains gains;
  for (std::size_t k = 0; k < kDoubles.size(); ++k) gains.values[k] = pid.value(kDoubles[k].name, 0.0);
  gains.antiwindup = pid.value(kAntiwindup, false);
  return gains;
}

dr::Config toConfig(const Gains& gains) {
  dr::Config config;
  for (std::size_t k = 0; k < kDoubles.size(); ++k) {
    dr::DoubleParameter parameter;
    parameter.name = kDoubles[k].name;
    parameter.value = gains.values[k];
    config.doubles.push_back(parameter);
  }
  dr::BoolParameter antiwindup;
  antiwindup.name = kAntiwindup;
  antiwindup.value = gains.antiwindup;
  config.bools.push_back(antiwindup);
  dr::GroupState group;
  group.name = kGroup;
  group.state = true;
  group.id = 0;
  group.parent = 0;
  config.groups.push_back(group);
  return config;
}

dr::ConfigDescription description() {
  dr::ConfigDescription description;
  dr::Group group;
  group.name = kGroup;
  group.id = 0;
  group.parent = 0;
  Gains minimum, maximum, defaults;
  for (std::size_t k = 0; k < kDoubles.size(); ++k) {
    dr::ParamDescription parameter;
    parameter.name = kDoubles[k].name;
    parameter.type = "double";
    parameter.level = 1;
    parameter.description = kDoubles[k].meaning;
    group.parameters.push_back(parameter);
    minimum.values[k] = kDoubles[k].min;
    maximum.values[k] = kDoubles[k].max;
    defaults.values[k] = kDoubles[k].default_value;
  }
  dr::ParamDescription antiwindup;
  antiwindup.name = kAntiwindup;
  antiwindup.type = "bool";
  antiwindup.level = 1;
  antiwindup.description = "keep the integral error where the integral term stays inside its bounds";
  group.parameters.push_back(antiwindup);
  maximum.antiwindup = true;
  description.groups.push_back(group);
  description.min = toConfig(minimum);
  description.max = toConfig(maximum);
  description.dflt = toConfig(defaults);
  return description;
}

// The gains of `pid` in a control.gains reply; false when it has none of that name.
bool findGains(const json& reply, const std::string& pid, Gains& gains) {
  for (const json& entry : reply.value("pids", json::array())) {
    if (entry.value("name", "") == pid) {
      gains = gainsFromJson(entry);
      return true;
    }
  }
  return false;
}

}  // namespace

// What a set_parameters call needs; shared with the service's callback, so a
// call in flight keeps it alive while its controller is unloaded.
struct PidState {
  std::string controller;
  std::string pid;
  std::string ros_namespace;  // <ns>/<controller>/<pid>
  ros::Publisher updates;
  std::mutex mutex;  // one set at a time; guards published
  Gains published;
};

struct PidReconfigureServers::Server {
  std::shared_ptr<PidState> state;
  ros::Publisher descriptions;
  ros::ServiceServer service;
};

namespace {

// The parameters to the ROS parameter server, as a dynamic_reconfigure server
// writes them after a change.
void writeParameters(const std::string& ros_namespace, const Gains& gains) {
  for (std::size_t k = 0; k < kDoubles.size(); ++k) {
    ros::param::set(ros_namespace + "/" + kDoubles[k].name, gains.values[k]);
  }
  ros::param::set(ros_namespace + "/" + kAntiwindup, gains.antiwindup);
}

bool setParameters(NodeLink& link, PidState& state, const dr::Config& requested, dr::Config& reply) {
  std::lock_guard lock(state.mutex);
  json args = {{"controller", state.controller}, {"pid", state.pid}};
  // Unknown names are ignored, as a dynamic_reconfigure server ignores them;
  // a value that is not a number leaves its gain as it is.
  const auto take = [&args, &state](const std::string& name, double value) {
    for (const DoubleParameter& parameter : kDoubles) {
      if (name != parameter.name) continue;
      if (std::isnan(value)) {
        ROS_ERROR("%s/set_parameters: %s is nan; it stays as it is", state.ros_namespace.c_str(), name.c_str());
        continue;
      }
      args[name] = std::clamp(value, parameter.min, parameter.max);
    }
  };
  for (const dr::DoubleParameter& parameter : requested.doubles) take(parameter.name, parameter.value);
  for (const dr::IntParameter& parameter : requested.ints) take(parameter.name, parameter.value);
  for (const dr::BoolParameter& parameter : requested.bools) {
    if (parameter.name == kAntiwindup) args[kAntiwindup] = static_cast<bool>(parameter.value);
  }
  json answer;
  try {
    answer = link.call("control.gains", args);
  } catch (const std::exception& e) {
    ROS_ERROR("%s/set_parameters: %s; the gains stay as they are", state.ros_namespace.c_str(), e.what());
    try {
      answer = link.call("control.gains", {{"controller", state.controller}});
    } catch (const std::exception& again) {
      ROS_ERROR("%s/set_parameters: %s", state.ros_namespace.c_str(), again.what());
      return false;
    }
  }
  Gains gains;
  if (!findGains(answer, state.pid, gains)) return false;
  reply = toConfig(gains);
  writeParameters(state.ros_namespace, gains);
  state.published = gains;
  state.updates.publish(reply);
  return true;
}

}  // namespace

PidReconfigureServers::PidReconfigureServers(ros::NodeHandle& nh, NodeLink& link) : nh_(nh), link_(link) {}

PidReconfigureServers::~PidReconfigureServers() = default;

void PidReconfigureServers::discover() {
  std::map<std::string, std::pair<std::string, json>> present;  // key -> (controller, PID's gains)
  for (const json& controller : link_.call("control.list").value("controllers", json::array())) {
    const std::string name = controller.value("name", "");
    json reply;
    try {
      reply = link_.call("control.gains", {{"controller", name}});
    } catch (const std::exception&) {
      continue;  // unloaded since the list
    }
    for (const json& pid : reply.value("pids", json::array())) {
      present[name + "/" + pid.value("name", "")] = {name, pid};
    }
  }
  for (auto it = servers_.begin(); it != servers_.end();) {
    it = present.count(it->first) != 0 ? std::next(it) : servers_.erase(it);
  }
  for (const auto& [key, found] : present) {
    const Gains gains = gainsFromJson(found.second);
    auto existing = servers_.find(key);
    if (existing != servers_.end()) {
      // Changed elsewhere (`servoloop control gains`, a reload): ROS hears of it.
      PidState& state = *existing->second->state;
      std::lock_guard state_lock(state.mutex);
      if (!(state.published == gains)) {
        state.published = gains;
        writeParameters(state.ros_namespace, gains);
        state.updates.publish(toConfig(gains));
      }
      continue;
    }
    auto state = std::make_shared<PidState>();
    state->controller = found.first;
    state->pid = found.second.value("name", "");
    state->ros_namespace = link_.resolve(key);
    state->published = gains;
    auto server = std::make_unique<Server>();
    server->state = state;
    server->descriptions = nh_.advertise<dr::ConfigDescription>(state->ros_namespace + "/parameter_descriptions", 1, true);
    state->updates = nh_.advertise<dr::Config>(state->ros_namespace + "/parameter_updates", 1, true);
    server->descriptions.publish(description());
    state->updates.publish(toConfig(gains));
    NodeLink& link = link_;
    server->service = nh_.advertiseService<dr::Reconfigure::Request, dr::Reconfigure::Response>(
        state->ros_namespace + "/set_parameters",
        [&link, state](dr::Reconfigure::Request& request, dr::Reconfigure::Response& response) {
          return setParameters(link, *state, request.config, response.config);
        });
    servers_.emplace(key, std::move(server));
  }
}

}  // namespace servoloop::ros1
