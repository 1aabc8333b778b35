#include "gazebo_services.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <thread>

#include <gazebo_msgs/ApplyJointEffort.h>
#include <gazebo_msgs/GetJointProperties.h>
#include <gazebo_msgs/SetModelConfiguration.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>
#include <tinyxml2.h>

namespace servoloop::ros1 {

using nlohmann::json;

std::map<std::string, UrdfJoint> urdfJoints(const std::string& urdf_xml) {
  tinyxml2::XMLDocument document;
  if (document.Parse(urdf_xml.c_str(), urdf_xml.size()) != tinyxml2::XML_SUCCESS) {
    throw std::runtime_error(std::string("the robot description does not read as XML: ") + document.ErrorStr());
  }
  const tinyxml2::XMLElement* robot = document.FirstChildElement("robot");
  if (robot == nullptr) throw std::runtime_error("the robot description has no <robot> element");
  std::map<std::string, UrdfJoint> joints;
  for (const auto* joint = robot->FirstChildElement("joint"); joint != nullptr; joint = joint->NextSiblingElement("joint")) {
    const char* name = joint->Attribute("name");
    const char* type = joint->Attribute("type");
    if (name == nullptr || type == nullptr) continue;  // a <gazebo> or transmission <joint> reference
    UrdfJoint out;
    const std::string kind = type;
    if (kind == "revolute") out.gazebo_type = gazebo_msgs::GetJointProperties::Response::REVOLUTE;
    else if (kind == "continuous") out.gazebo_type = gazebo_msgs::GetJointProperties::Response::CONTINUOUS;
    else if (kind == "prismatic") out.gazebo_type = gazebo_msgs::GetJointProperties::Response::PRISMATIC;
    else if (kind == "fixed") out.gazebo_type = gazebo_msgs::GetJointProperties::Response::FIXED;
    else if (kind == "floating") out.gazebo_type = gazebo_msgs::GetJointProperties::Response::BALL;
    else out.gazebo_type = gazebo_msgs::GetJointProperties::Response::UNIVERSAL;  // planar: two DOF
    if (const auto* dynamics = joint->FirstChildElement("dynamics")) out.damping = dynamics->DoubleAttribute("damping", 0.0);
    joints[name] = out;
  }
  return joints;
}

void EffortSchedule::apply(double effort, double start_s, double duration_s, double now_s) {
  if (duration_s == 0.0 || !std::isfinite(effort)) return;
  // A start in the past (or 0) is now, as Gazebo moves it.
  const double start = std::max(start_s, now_s);
  const double end = duration_s < 0.0 ? std::numeric_limits<double>::infinity() : start + duration_s;
  entries_.push_back({effort, start, end});
}

double EffortSchedule::sumAt(double now_s) {
  entries_.erase(std::remove_if(entries_.begin(), entries_.end(), [now_s](const Entry& e) { return e.end_s <= now_s; }),
                 entries_.end());
  double sum = 0.0;
  for (const Entry& e : entries_) {
    if (e.start_s <= now_s) sum += e.effort;
  }
  return sum;
}

namespace {

// A reset or pause waits for the world's loop to stand between two cycles.
constexpr double kWorldCallTimeoutS = 30.0;

// Gazebo names a joint "joint1" or, scoped, "model::joint1".
std::string unscoped(const std::string& name) {
  const auto at = name.rfind("::");
  return at == std::string::npos ? name : name.substr(at + 2);
}

}  // namespace

GazeboServices::GazeboServices(ros::NodeHandle& nh, NodeLink& link, const RobotStateCache& state)
    : link_(link), state_(state), namespace_(link.nodeNamespace()) {
  const json description = link.call("robot.description");
  model_ = description.value("model", "");
  joints_ = urdfJoints(description.value("urdf", ""));

  servers_.push_back(nh.advertiseService<gazebo_msgs::GetJointProperties::Request, gazebo_msgs::GetJointProperties::Response>(
      "/gazebo/get_joint_properties",
      [this](gazebo_msgs::GetJointProperties::Request& request, gazebo_msgs::GetJointProperties::Response& response) {
        const std::string name = unscoped(request.joint_name);
        const auto joint = joints_.find(name);
        if (joint == joints_.end()) {
          response.success = false;
          response.status_message = "GetJointProperties: joint [" + request.joint_name + "] does not exist in " + model_;
          return true;
        }
        response.type = static_cast<std::uint8_t>(joint->second.gazebo_type);
        response.damping.push_back(joint->second.damping);
        // The first calls may come before the first joint state: wait for it
        // a little (a node written for Gazebo reads position[0] at once).
        for (int i = 0; i < 100 && !state_.joint(name); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
        if (const auto sample = state_.joint(name)) {
          response.position.push_back(sample->position);
          response.rate.push_back(sample->velocity);
          response.success = true;
          response.status_message = "GetJointProperties: got properties";
        } else {
          response.position.push_back(std::numeric_limits<double>::quiet_NaN());
          response.rate.push_back(std::numeric_limits<double>::quiet_NaN());
          response.success = false;
          response.status_message = "GetJointProperties: no joint state of [" + name +
                                    "] yet: a joint_state_controller must run on " + namespace_;
        }
        return true;
      }));

  servers_.push_back(nh.advertiseService<gazebo_msgs::ApplyJointEffort::Request, gazebo_msgs::ApplyJointEffort::Response>(
      "/gazebo/apply_joint_effort",
      [this](gazebo_msgs::ApplyJointEffort::Request& request, gazebo_msgs::ApplyJointEffort::Response& response) {
        const std::string name = unscoped(request.joint_name);
        if (joints_.count(name) == 0) {
          response.success = false;
          response.status_message = "ApplyJointEffort: joint [" + request.joint_name + "] does not exist in " + model_;
          return true;
        }
        if (!std::isfinite(request.effort)) {
          response.success = false;
          response.status_message = "ApplyJointEffort: effort " + std::to_string(request.effort) + " is not a finite number";
          return true;
        }
        std::string why;
        const std::string topic = effortTopicFor(name, why);
        if (topic.empty()) {
          response.success = false;
          response.status_message = "ApplyJointEffort: " + why;
          return true;
        }
        {
          std::lock_guard lock(mutex_);
          schedules_[topic].apply(request.effort, request.start_time.toSec(), request.duration.toSec(), simTime());
        }
        tick();  // an effort that starts now is sent now
        response.success = true;
        response.status_message = "ApplyJointEffort: effort set";
        return true;
      }));

  // The world's controls. std_srvs/Empty has no way to say "failed" but
  // returning false, which rosservice reports as a failed call; the reason
  // goes to the log.
  const auto world_control = [this](const char* service, const char* op) {
    return [this, service, op](std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
      try {
        link_.call(op, json::object(), kWorldCallTimeoutS);
        if (std::string(op) == "world.reset") {
          // The effort controllers start again at zero: the efforts still
          // applied are sent again at the next tick.
          std::lock_guard lock(mutex_);
          published_.clear();
        }
        return true;
      } catch (const std::exception& e) {
        ROS_ERROR("%s: %s", service, e.what());
        return false;
      }
    };
  };
  // Gazebo's reset_world keeps the simulated time; servoloop resets both
  // (a world's time and its bodies' state go back together), so both
  // services do what reset_simulation does.
  for (const auto& [service, op] : {std::pair{"/gazebo/reset_simulation", "world.reset"},
                                    std::pair{"/gazebo/reset_world", "world.reset"},
                                    std::pair{"/gazebo/pause_physics", "world.pause"},
                                    std::pair{"/gazebo/unpause_physics", "world.unpause"}}) {
    servers_.push_back(
        nh.advertiseService<std_srvs::Empty::Request, std_srvs::Empty::Response>(service, world_control(service, op)));
  }

  servers_.push_back(
      nh.advertiseService<gazebo_msgs::SetModelConfiguration::Request, gazebo_msgs::SetModelConfiguration::Response>(
          "/gazebo/set_model_configuration",
          [this](gazebo_msgs::SetModelConfiguration::Request& request,
                 gazebo_msgs::SetModelConfiguration::Response& response) {
            try {
              link_.call("model.set_configuration", {{"model", request.model_name},
                                                     {"joint_names", request.joint_names},
                                                     {"joint_positions", request.joint_positions}});
              response.success = true;
              response.status_message = "SetModelConfiguration: success";
            } catch (const std::exception& e) {
              response.success = false;
              response.status_message = std::string("SetModelConfiguration: ") + e.what();
            }
            return true;
          }));

  ticker_ = std::thread([this] {
    while (!stop_.load()) {
      tick();
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  });
}

GazeboServices::~GazeboServices() {
  stop_.store(true);
  if (ticker_.joinable()) ticker_.join();
  // What the bridge applied ends with it.
  std::lock_guard lock(mutex_);
  for (const auto& [topic, sum] : published_) {
    if (sum == 0.0) continue;
    try {
      link_.call("topic.pub", {{"topic", topic}, {"type", "std_msgs/Float64"}, {"msg", {{"data", 0.0}}}}, 2.0);
    } catch (const std::exception&) {
      // The node is gone: nothing to undo.
    }
  }
}

std::string GazeboServices::effortTopicFor(const std::string& joint, std::string& why) {
  // The controller list, read at most once a second (a node written for
  // Gazebo calls at 100 Hz or more).
  const auto now = std::chrono::steady_clock::now();
  json reply;
  {
    std::lock_guard lock(controllers_mutex_);
    if (now - controllers_read_ > std::chrono::seconds(1)) {
      controllers_ = link_.call("control.list").at("controllers");
      controllers_read_ = now;
    }
    reply = controllers_;
  }
  for (const json& controller : reply) {
    if (controller.value("type", "") != "effort_controllers/JointEffortController" ||
        controller.value("state", "") != "running") {
      continue;
    }
    for (const json& claim : controller.value("claimed_resources", json::array())) {
      const auto resources = claim.value("resources", std::vector<std::string>{});
      if (std::find(resources.begin(), resources.end(), joint) != resources.end()) {
        return link_.resolve(controller.value("name", "") + "/command");
      }
    }
  }
  why = "no running effort_controllers/JointEffortController claims [" + joint + "] in " + namespace_ +
        ": servoloop applies Gazebo joint efforts through one (add it to the controllers; docs/ros1.md)";
  return "";
}

double GazeboServices::simTime() {
  // The node's own clock: the bridged stamps reach the bridge in bursts (the
  // node delivers its bus to socket clients every 10 ms of simulated time).
  try {
    return link_.call("ping").value("sim_time", state_.simTime());
  } catch (const std::exception&) {
    return state_.simTime();
  }
}

void GazeboServices::tick() {
  // Under the lock from the sum to its publication, so two ticks (the
  // ticker's and a service call's) never send their sums out of order.
  std::lock_guard lock(mutex_);
  if (schedules_.empty()) return;
  const double now = simTime();
  for (auto it = schedules_.begin(); it != schedules_.end();) {
    const std::string& topic = it->first;
    const double sum = it->second.sumAt(now);
    const auto last = published_.find(topic);
    if (last != published_.end() && last->second == sum) {
      // Nothing left to apply and 0 sent: stop watching this topic.
      it = it->second.empty() && sum == 0.0 ? schedules_.erase(it) : std::next(it);
      continue;
    }
    published_[topic] = sum;
    try {
      link_.call("topic.pub", {{"topic", topic}, {"type", "std_msgs/Float64"}, {"msg", {{"data", sum}}}});
    } catch (const std::exception& e) {
      ROS_WARN("/gazebo/apply_joint_effort: %s not delivered: %s", topic.c_str(), e.what());
      published_.erase(topic);  // sent again at the next tick
    }
    ++it;
  }
}

}  // namespace servoloop::ros1
