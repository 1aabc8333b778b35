#pragma once
// A running servoloop node: one simulated world with its robots (each a
// RobotInstance with its own controller manager and topic bus), the
// parameter store they share, the recorders of the launch file, and the IPC
// servers the command line talks to (docs/node_operations.md).
//
//   Node node(loadLaunchFile("robots/one_dof/one_dof_w_jnt_ctl.launch.yaml"), options);
//   node.start();
//   node.waitUntilDone();   // until the duration has run, or requestShutdown()
//   node.shutdown();
//   std::cout << toText(node.summary());
//
// The world: the backend's shared physics world (plugin "<backend>/world",
// where every simulated robot touches the others) or, for a backend without
// one, robots simulated apart; either way one loop (world/world_loop.hpp)
// runs every simulated robot's cycles in lockstep and steps the physics.
//
// Threads: the world loop's (the real-time thread of every simulated robot),
// one loop thread per robot on the wall clock (hardware, or world.clock:
// wall), one delivery thread per robot's bus, one service thread per IPC
// socket plus a worker for operations that wait on a loop (load, unload,
// switch), and the caller's thread, which waits in waitUntilDone() and logs
// the controllers' and hardware's faults. Public members are non-real-time
// and safe from any thread unless noted.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "servoloop/ipc/ipc_server.hpp"
#include "servoloop/node/launch_file.hpp"
#include "servoloop/node/model_states_publisher.hpp"
#include "servoloop/node/robot_instance.hpp"
#include "servoloop/node/run_summary.hpp"
#include "servoloop/node/topic_recorder.hpp"
#include "servoloop/node/world_snapshot.hpp"
#include "servoloop/params/parameter_store.hpp"
#include "servoloop/plugin/plugin_loader.hpp"
#include "servoloop/world/world_loop.hpp"

namespace servoloop::node {

class NodeOperations;  // node_operations.hpp

struct NodeOptions {
  // Simulated seconds to run, then end; unset: run until requestShutdown().
  std::optional<double> duration_s;
  // Overrides the launch file's world.real_time_factor; when neither is set:
  // 0 (free-running) with a duration, 1 without.
  std::optional<double> real_time_factor;
  // Overrides the launch file's world.backend.
  std::optional<std::string> backend;
  // Overrides the launch file's world.clock (true: wall).
  std::optional<bool> wall_clock;
  // Serve the IPC sockets (one per robot namespace; default.sock when the
  // world has no robot). Off for in-process tests that need no socket.
  bool serve_ipc = true;
  // Searched before SERVOLOOP_PLUGIN_PATH and the default plugin folder.
  std::vector<std::filesystem::path> plugin_directories;
  // The world starts paused (its robots' launch controllers start; no
  // physics step until unpauseWorld() or stepWorld()).
  bool start_paused = false;
  // Parameters set after each robot's parameter files are loaded and before
  // its controllers load (full names, e.g.
  // /one_DOF_robot/joint1_position_controller/pid/p): a run's own values.
  std::vector<std::pair<std::string, YAML::Node>> parameter_overrides;
};

// A model's state in the world frame, as Gazebo's get_model_state gives it.
struct ModelState {
  std::string name;        // the model (URDF robot) name
  std::string ns;          // its namespace
  bool fixed = false;      // a fixed base: at its spawn pose, at rest
  double position[3] = {0.0, 0.0, 0.0};          // m
  double orientation[4] = {0.0, 0.0, 0.0, 1.0};  // quaternion x, y, z, w
  double linear_velocity[3] = {0.0, 0.0, 0.0};   // m/s, world axes
  double angular_velocity[3] = {0.0, 0.0, 0.0};  // rad/s, world axes
};

// What set_model_state gives: a pose (orientation x, y, z, w; normalised)
// and a twist (world axes).
struct ModelPose {
  double position[3] = {0.0, 0.0, 0.0};
  double orientation[4] = {0.0, 0.0, 0.0, 1.0};
};
struct ModelTwist {
  double linear[3] = {0.0, 0.0, 0.0};
  double angular[3] = {0.0, 0.0, 0.0};
};

// Where the world stands (world.state).
struct WorldState {
  bool paused = false;
  std::uint64_t steps = 0;  // physics steps since the start or the last reset
  double sim_time_s = 0.0;  // the longest simulated time of any robot, s
};

class Node {
 public:
  // Builds the world: loads every robot's parameter files, spawns the robots
  // (backend, controllers), creates the recorders and queues the timed
  // publications. Nothing runs yet. Throws ConfigError naming the launch file
  // (or URDF, YAML, backend) and the fix.
  Node(LaunchFile launch, NodeOptions options);
  // shutdown().
  ~Node();
  Node(const Node&) = delete;
  Node& operator=(const Node&) = delete;

  // Starts the IPC servers and every robot's loop. Throws servoloop::Error if
  // a socket is taken by another node.
  void start();

  // Blocks until every robot has run its duration, the loops stopped on their
  // own, or requestShutdown() was called. Every `tick_period` it logs the
  // controllers' and hardware's new faults and calls `tick` (progress display).
  // Without a duration and with no robots, only requestShutdown() ends it.
  void waitUntilDone(const std::function<void()>& tick = {},
                     std::chrono::milliseconds tick_period = std::chrono::milliseconds(100));

  // Any thread, async-signal-safe (one atomic store): ends waitUntilDone().
  void requestShutdown() noexcept { shutdown_requested_.store(true); }
  bool shutdownRequested() const noexcept { return shutdown_requested_.load(); }

  // Closes the sockets, stops every loop, captures the summary, delivers what
  // is still queued on the buses and closes the recordings, then stops and
  // unloads every controller. Idempotent; call from the thread that owns the
  // node (not from an IPC handler: use requestShutdown there).
  void shutdown();

  // The end-of-run summary; captured by shutdown(), or taken now (loops
  // possibly running) before it.
  RunSummary summary();

  // model.spawn: adds a robot to the world (loading its params files first)
  // and, once the node runs, starts its loop and its IPC server. Returns its
  // namespace. Throws ConfigError like the constructor, or servoloop::Error if
  // a robot with that namespace exists.
  std::string spawnRobot(const RobotSpec& spec);

  // World control, as Gazebo's pause_physics, unpause_physics, the step
  // button and reset_simulation (docs/simulation.md). They act on the
  // simulated world's loop; a node with no such loop (world.clock: wall)
  // refuses them with servoloop::Error, as resetWorld() does for a world
  // with a robot on hardware.
  void pauseWorld();
  void unpauseWorld();
  // While paused: `cycles` physics steps (and the control cycles on them);
  // returns the steps run (fewer when no robot cycles).
  std::uint64_t stepWorld(std::uint64_t cycles);
  // Every robot and object back at its start, atomically between two cycles
  // (RobotInstance::resetToStart), then the world restarted (its time 0,
  // SimulatedWorld::restart); a paused world stays paused. Returns what did
  // not come back (controllers that did not start again), empty when all did.
  // A controller with a parameter under one of `changed_parameters` (full
  // names) is reloaded on the way, so that it reads the new values.
  std::string resetWorld(const std::vector<std::string>& changed_parameters = {});
  WorldState worldState() const;
  // Gazebo's set_model_configuration: the named joints of the robot with
  // that namespace or model name moved to `positions`, at rest, between two
  // cycles. Throws servoloop::Error for an unknown model or joint, a
  // non-finite position, or a robot on hardware.
  void setModelConfiguration(const std::string& model, const std::vector<std::string>& joints,
                             const std::vector<double>& positions);
  // Gazebo's set_model_state: the floating base of the robot with that
  // namespace or model name teleported, between two cycles, to `pose`
  // and/or moving with `twist` (world frame and axes, as modelState() gives
  // them); what is not given stays as it is, and the joints keep their
  // state. Throws servoloop::Error for an unknown model, a fixed base, a
  // robot on hardware, or a value that is not a finite number (nothing moved).
  void setModelState(const std::string& model, const std::optional<ModelPose>& pose,
                     const std::optional<ModelTwist>& twist);
  // Gazebo's delete_model: the robot with that namespace or model name
  // taken out of the world. Its running controllers are stopped first (with
  // a log line) and all are unloaded, its recordings closed, its socket
  // closed and its bodies removed between two cycles; the other robots run
  // on. Returns its namespace. Throws servoloop::Error naming the models
  // there are for an unknown one. Called over the robot's own socket, the
  // socket closes and the bodies go just after the reply.
  std::string deleteModel(const std::string& model);
  // The robot with that namespace ("/name" or "name") or model name, or nullptr.
  RobotInstance* findModel(const std::string& model);
  // The robot whose bus carries `topic`: the one with the longest namespace
  // holding it, else the first robot; nullptr in a world with no robot.
  RobotInstance* robotForTopic(const std::string& topic);
  // A model's pose and twist: a floating base's ground truth (exact while
  // the world is paused, else of a recent step), a fixed base's spawn pose.
  // Throws servoloop::Error naming the models there are for an unknown one.
  ModelState modelState(const std::string& model);

  // What a viewer draws: every simulated model's base pose and joint
  // positions, taken between two segments of cycles (world_snapshot.hpp).
  // The first call starts the snapshots (60 per second of world time); a
  // paused world is copied on each call. False for a world on the wall
  // clock, which has no world loop to take them.
  bool worldFrame(WorldSnapshot::Frame& out);

  // The robot of a namespace, or nullptr. Robots live until the node is destroyed.
  RobotInstance* findRobot(const std::string& robot_namespace);
  std::vector<std::string> robotNamespaces() const;
  std::vector<RobotInstance*> robots() const;

  params::ParameterStore& parameters() { return parameters_; }
  plugin::PluginLoader& plugins() { return *plugins_; }
  // Longest simulated time of any robot, s.
  double simTime() const;
  const std::optional<double>& duration() const { return options_.duration_s; }
  double realTimeFactor() const { return real_time_factor_; }
  const LaunchFile& launchFile() const { return launch_; }
  // The recordings, with their files (for plotting after the run).
  const std::vector<RecordSpec>& recordings() const { return launch_.record; }

 private:
  void createWorld();
  // The models /gazebo/model_states lists (and the bus carrying it), after
  // a robot joined or left.
  void refreshModelStates();
  // Runs `change` (adding a robot to the world, or taking one out) between
  // two cycles of the world loop when the robots touch, at once otherwise.
  void changeWorld(const std::function<void()>& change);
  world::WorldLoop& requireWorldLoop(const char* what) const;
  void startRobotLocked(RobotInstance& robot);
  void startServer(const std::string& socket_namespace, RobotInstance* robot);

  LaunchFile launch_;
  NodeOptions options_;
  double real_time_factor_ = 0.0;
  std::shared_ptr<plugin::PluginLoader> plugins_;
  params::ParameterStore parameters_;

  // The simulated world and its loop (declared before robots_: the robots,
  // built into the world and members of the loop, go first).
  plugin::PluginPtr<hardware_interface::SimulatedWorld> world_plugin_;  // the backend's shared world
  std::unique_ptr<hardware_interface::SimulatedWorld> separate_worlds_;  // or robots simulated apart
  hardware_interface::SimulatedWorld* world_ = nullptr;
  std::unique_ptr<ModelStatesPublisher> model_states_;  // the world loop's observer
  std::unique_ptr<WorldSnapshot> world_snapshot_;  // the world loop's observer, for viewers
  std::mutex model_states_mutex_;  // one refreshModelStates() at a time
  std::unique_ptr<world::WorldLoop> world_loop_;

  // Woken by a robot whose loop has ended (declared before robots_, whose
  // loop threads call into it, so that it outlives them).
  std::mutex finished_mutex_;
  std::condition_variable finished_wake_;
  bool robot_finished_ = false;  // under finished_mutex_

  // The robots' namespaces, taken while a robot is built (never held while
  // waiting for the world loop).
  std::mutex namespaces_mutex_;
  std::set<std::string> namespaces_;

  mutable std::mutex robots_mutex_;
  std::vector<std::unique_ptr<RobotInstance>> robots_;
  std::vector<std::unique_ptr<TopicRecorder>> recorders_;
  std::vector<std::unique_ptr<NodeOperations>> operations_;
  std::vector<std::unique_ptr<ipc::IpcServer>> servers_;
  bool started_ = false;
  bool shut_down_ = false;
  bool accepting_robots_ = true;  // cleared (under robots_mutex_) when shutdown begins
  // Finishing deleteModel() for robots deleted over their own socket
  // (under robots_mutex_; joined when shutdown begins).
  std::vector<std::thread> model_reapers_;
  std::chrono::steady_clock::time_point start_time_{};
  std::optional<RunSummary> final_summary_;

  std::atomic<bool> shutdown_requested_{false};
};

}  // namespace servoloop::node
