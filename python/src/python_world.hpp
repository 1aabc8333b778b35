#pragma once
// The Python package's World (python/servoloop): a node run in-process, with
// no socket, its world paused between calls and stepped by them. Plain C++
// (no Python type here): world_module.cpp binds it, converting values as
// JSON text and arrays, and releasing the GIL while it steps.
//
// Threading: one World is used by one Python thread at a time: a call that
// steps, resets, sets a parameter or closes while another of these runs in
// another thread is refused (servoloop::Error). Worlds in several threads
// run in parallel.
#include <cstdint>
#include <atomic>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "servoloop/node/node.hpp"

namespace servoloop::python {

struct WorldOptions {
  std::optional<std::string> backend;           // overrides the launch file's world.backend
  std::map<std::string, std::string> params;    // full name -> value as JSON text
  std::string log_level = "warn";               // the node's log level (trace .. off)
};

// The joint states of one robot, in the robot's joint order.
struct JointStates {
  std::vector<std::string> name;
  std::vector<double> position;  // rad or m
  std::vector<double> velocity;  // rad/s or m/s
  std::vector<double> effort;    // N·m or N
};

class World {
 public:
  // Loads the launch file (relative to the current folder), builds the world
  // paused and starts it: the launch file's controllers run, time is 0.
  // Throws servoloop::ConfigError / Error with the command line's messages.
  World(const std::string& launch_file, const WorldOptions& options);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // Every robot and object back at its start, controllers restarted (those
  // whose parameters set_param changed are reloaded), time 0.
  void reset();
  // Physics steps of `seconds` simulated time (rounded to whole steps; at
  // least 0). Returns the steps run.
  std::uint64_t step(double seconds);
  std::uint64_t stepCycles(std::uint64_t cycles);
  double time() const;
  double timeStep() const;
  std::vector<std::string> namespaces() const;
  // Every robot's topics: {name: type} ("" while a topic has no type yet).
  std::map<std::string, std::string> topics() const;

  // A message on a robot's topic (the robot whose namespace holds the topic),
  // delivered before the next step. `value` is JSON: a number (std_msgs/Float64),
  // a list (Float64MultiArray) or a message's fields; `type` as the command line's.
  void publish(const std::string& topic, const nlohmann::json& value, const std::string& type);
  // The messages on `topic` since the last call, each {stamp, type, msg};
  // the first call subscribes and returns none.
  nlohmann::json subscribe(const std::string& topic);

  // A robot's joints (robot_namespace empty: the world's only robot).
  JointStates jointState(const std::string& robot_namespace) const;
  // A model's pose and twist in the world frame (name: its namespace with
  // or without the leading '/', or its model name).
  nlohmann::json modelState(const std::string& name) const;
  // Gazebo's set_model_state: `request` {model, pose?, twist?} as
  // modelState() gives them; returns the new state.
  nlohmann::json setModelState(const nlohmann::json& request);

  // value: JSON text. A controller's parameter takes effect at the next reset.
  void setParam(const std::string& name, const std::string& value_json);
  nlohmann::json getParam(const std::string& name) const;

  // Stops the world (idempotent); every later call fails.
  void close();

 private:
  node::Node& node() const;
  node::RobotInstance& robotFor(const std::string& robot_namespace) const;
  node::RobotInstance& robotForTopic(const std::string& topic) const;
  std::string robotNames() const;  // the robots' namespaces, for messages
  void flushBuses() const;

  // Marks the World busy for one call (see Threading); throws when it is.
  class Busy {
   public:
    explicit Busy(std::atomic<bool>& busy);
    ~Busy() { busy_.store(false); }
    Busy(const Busy&) = delete;
    Busy& operator=(const Busy&) = delete;

   private:
    std::atomic<bool>& busy_;
  };

  std::atomic<bool> busy_{false};
  std::unique_ptr<node::Node> node_;
  double time_step_s_ = 0.001;
  std::vector<std::string> changed_parameters_;  // since the last reset

  struct Inbox {
    std::mutex mutex;
    std::deque<nlohmann::json> messages;
    realtime::Subscription subscription;
  };
  std::map<std::string, std::unique_ptr<Inbox>> inboxes_;
};

}  // namespace servoloop::python
