// The node: a world of robots, its recorders and its IPC sockets.
#include "servoloop/node/node.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <thread>

#include <fmt/format.h>

#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/ipc/ipc_socket_path.hpp"
#include "servoloop/node/message_json.hpp"
#include "servoloop/node/node_operations.hpp"
#include "servoloop/node/realtime_settings.hpp"
#include "servoloop/node/robot_namespace.hpp"
#include "servoloop/plugin/plugin_path.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::node {
namespace {

// True if topic lies under namespace ns ("/a" holds "/a/b", "/" holds everything).
bool topicUnder(const std::string& topic, const std::string& ns) {
  if (ns == "/") return true;
  return topic.size() > ns.size() && topic.compare(0, ns.size(), ns) == 0 && topic[ns.size()] == '/';
}

}  // namespace

Node::Node(LaunchFile launch, NodeOptions options) : launch_(std::move(launch)), options_(std::move(options)) {
  if (options_.backend) launch_.world.backend = *options_.backend;
  if (options_.wall_clock) launch_.world.wall_clock = *options_.wall_clock;
  real_time_factor_ = options_.real_time_factor.value_or(
      launch_.world.real_time_factor.value_or(options_.duration_s ? 0.0 : 1.0));
  if (options_.duration_s && !(*options_.duration_s >= 0.0)) {
    throw Error(fmt::format("the duration {} s must be >= 0", *options_.duration_s));
  }
  if (!(real_time_factor_ >= 0.0)) {
    throw Error(fmt::format("the real-time factor {} must be >= 0 (0 runs as fast as possible)", real_time_factor_));
  }
  plugins_ = std::make_shared<plugin::PluginLoader>(plugin::pluginSearchPath(options_.plugin_directories));
  createWorld();

  for (const RobotSpec& spec : launch_.robots) spawnRobot(spec);

  for (const TimedPublication& written : launch_.publish) {
    RobotInstance* robot = robotForTopic(written.topic);
    if (robot == nullptr) {
      throw ConfigError(fmt::format("{}: publication on '{}': the world has no robot to publish to; add one under robots:",
                                    launch_.source.string(), written.topic));
    }
    // One given without a type takes the type its topic carries (a
    // trajectory controller's command topic takes a trajectory); a topic the
    // controllers created with another type than the one given would refuse
    // the message at its time. Both are said now, before the run.
    const realtime::TopicBus& bus = robot->topics();
    const std::string carried = bus.hasTopic(written.topic) ? bus.typeOf(written.topic) : "";
    TimedPublication publication;
    try {
      publication = withTopicType(written, carried);
      requireTopicType(bus, publication.topic, publication.type);
    } catch (const Error& e) {
      throw ConfigError(written.type_inferred ? std::string(e.what())
                                              : fmt::format("{}: publication: {}", launch_.source.string(), e.what()));
    }
    robot->addTimedPublication(publication);
  }
  for (const RecordSpec& record : launch_.record) {
    RobotInstance* robot = robotForTopic(record.topic);
    if (robot == nullptr) {
      throw ConfigError(fmt::format("{}: recording '{}': the world has no robot whose topics could be recorded",
                                    launch_.source.string(), record.topic));
    }
    recorders_.push_back(std::make_unique<TopicRecorder>(robot->topics(), record.topic, record.file));
  }
}

void Node::createWorld() {
  if (launch_.world.wall_clock) return;  // every robot on a loop thread of its own
  const std::string world_type = launch_.world.backend + "/world";
  hardware_interface::SimulatedWorldSettings settings;
  settings.time_step_s = launch_.world.time_step_s;
  settings.gravity = launch_.world.gravity;
  settings.ground_plane = launch_.world.ground_plane;
  if (launch_.world.shared && plugins_->hasType(world_type)) {
    try {
      world_plugin_ = plugins_->create<hardware_interface::SimulatedWorld>(world_type);
      world_plugin_->init(settings);
    } catch (const std::exception& e) {
      throw ConfigError(fmt::format("{}: world of the '{}' backend: {}", launch_.source.string(),
                                    launch_.world.backend, e.what()));
    }
    world_ = world_plugin_.get();
  } else {
    separate_worlds_ = std::make_unique<hardware_interface::SeparateWorlds>();
    separate_worlds_->init(settings);
    world_ = separate_worlds_.get();
  }
  world::WorldLoopOptions options;
  options.real_time_factor = real_time_factor_;
  if (!launch_.realtime.empty()) {
    options.on_thread_start = [realtime = launch_.realtime] { applyRealtimeSettings(realtime, "the world loop"); };
  }
  world_loop_ = std::make_unique<world::WorldLoop>(*world_, std::move(options));
  model_states_ = std::make_unique<ModelStatesPublisher>(settings.time_step_s);
  world_loop_->addObserver(*model_states_);
  world_snapshot_ = std::make_unique<WorldSnapshot>(settings.time_step_s);
  world_loop_->addObserver(*world_snapshot_);
  if (options_.start_paused) world_loop_->pause();
}

world::WorldLoop& Node::requireWorldLoop(const char* what) const {
  if (!world_loop_) {
    throw Error(fmt::format("{}: this world runs on the wall clock (world.clock: wall): its robots keep their own time, "
                            "so it cannot be paused, stepped or reset",
                            what));
  }
  return *world_loop_;
}

void Node::pauseWorld() { requireWorldLoop("pause").pause(); }

void Node::unpauseWorld() { requireWorldLoop("unpause").unpause(); }

std::uint64_t Node::stepWorld(std::uint64_t cycles) {
  world::WorldLoop& loop = requireWorldLoop("step");
  if (!started_) throw Error("step: the world has not started yet");
  return loop.stepPaused(cycles);
}

std::string Node::resetWorld(const std::vector<std::string>& changed_parameters) {
  world::WorldLoop& loop = requireWorldLoop("reset");
  std::string failures;
  std::lock_guard lock(robots_mutex_);  // no robot joins or leaves meanwhile
  loop.whilePaused([&] {
    // Every robot checked before any changes: the world resets whole or not at all.
    for (const auto& robot : robots_) robot->checkResettable();
    for (const auto& robot : robots_) {
      const std::string failed = robot->resetToStart(changed_parameters);
      if (!failed.empty()) failures += (failures.empty() ? "" : "; ") + robot->robotNamespace() + ": " + failed;
    }
    world_->restart();
    loop.rewindSteps();
  });
  return failures;
}

RobotInstance* Node::findModel(const std::string& model) {
  if (model.empty()) return nullptr;
  const std::string ns = model.front() == '/' ? model : "/" + model;
  std::lock_guard lock(robots_mutex_);
  for (const auto& robot : robots_) {
    if (robot->robotNamespace() == ns) return robot.get();
  }
  for (const auto& robot : robots_) {
    if (robot->robotName() == model) return robot.get();
  }
  return nullptr;
}

namespace {

std::string modelNames(const std::vector<std::string>& namespaces) {
  std::string names;
  for (const std::string& ns : namespaces) names += (names.empty() ? "" : ", ") + ns;
  return names;
}

}  // namespace

namespace {

// A fixed base's pose: where it was spawned (<ns>/sim/pose: x y z roll pitch yaw).
void spawnPose(const params::ParameterStore& parameters, const std::string& robot_namespace, double (&position)[3],
               double (&orientation)[4]) {
  const std::string ns = robot_namespace == "/" ? "" : robot_namespace;
  std::vector<double> pose = parameters.get<std::vector<double>>(ns + "/sim/pose", std::vector<double>(6, 0.0));
  pose.resize(6, 0.0);
  std::copy(pose.begin(), pose.begin() + 3, position);
  const double cr = std::cos(pose[3] / 2), sr = std::sin(pose[3] / 2);
  const double cp = std::cos(pose[4] / 2), sp = std::sin(pose[4] / 2);
  const double cy = std::cos(pose[5] / 2), sy = std::sin(pose[5] / 2);
  orientation[0] = sr * cp * cy - cr * sp * sy;
  orientation[1] = cr * sp * cy + sr * cp * sy;
  orientation[2] = cr * cp * sy - sr * sp * cy;
  orientation[3] = cr * cp * cy + sr * sp * sy;
}

}  // namespace

void Node::refreshModelStates() {
  if (!world_loop_ || !model_states_) return;
  std::lock_guard serial(model_states_mutex_);
  struct Entry {
    ModelStatesPublisher::Model model;
    const hardware_interface::SimulatedRobotHW* hardware;
    std::string robot_namespace;
    WorldSnapshot::Model snapshot;
  };
  std::vector<Entry> entries;
  realtime::TopicBus* bus = nullptr;
  {
    std::lock_guard lock(robots_mutex_);
    std::size_t best_length = 0;
    std::map<std::string, int> name_count;
    for (const auto& robot : robots_) ++name_count[robot->robotName()];
    for (const auto& robot : robots_) {
      auto* simulated = dynamic_cast<const hardware_interface::SimulatedRobotHW*>(&robot->hardware());
      if (simulated == nullptr || robot->wallClock()) continue;
      Entry entry{{}, simulated, robot->robotNamespace(), {}};
      entry.snapshot.ns = robot->robotNamespace();
      if (auto* state = robot->hardware().get<hardware_interface::JointStateInterface>()) {
        for (const std::string& joint : state->getNames()) {
          entry.snapshot.joint_names.push_back(joint);
          entry.snapshot.joint_positions.push_back(state->getHandle(joint).getPositionPtr());
        }
      }
      // Gazebo's model names are unique; robots of one URDF go by their namespace.
      entry.model.name = name_count[robot->robotName()] == 1 ? robot->robotName() : robot->robotNamespace().substr(1);
      entries.push_back(std::move(entry));
    }
    // The topic goes where `topic echo` looks for it (as robotForTopic picks).
    RobotInstance* carrier = robots_.empty() ? nullptr : robots_.front().get();
    for (const auto& robot : robots_) {
      const std::string& ns = robot->robotNamespace();
      if (topicUnder(ModelStatesPublisher::kTopic, ns) && ns.size() > best_length) {
        carrier = robot.get();
        best_length = ns.size();
      }
    }
    if (carrier != nullptr) bus = &carrier->topics();
  }
  // Whether a base floats is asked of its state, which only the world's
  // thread may read while the world runs: asked with the world paused.
  world_loop_->whilePaused([&] {
    std::vector<ModelStatesPublisher::Model> models;
    std::vector<WorldSnapshot::Model> snapshot_models;
    for (Entry& entry : entries) {
      hardware_interface::BaseGroundTruth probe;
      if (entry.hardware->readBaseGroundTruth(probe)) {
        entry.model.floating = entry.hardware;
        entry.snapshot.floating = entry.hardware;
      } else {
        double position[3];
        double orientation[4];
        spawnPose(parameters_, entry.robot_namespace, position, orientation);
        entry.model.fixed_pose.position = {position[0], position[1], position[2]};
        entry.model.fixed_pose.orientation = {orientation[0], orientation[1], orientation[2], orientation[3]};
        std::copy(std::begin(position), std::end(position), entry.snapshot.fixed_pose);
        std::copy(std::begin(orientation), std::end(orientation), entry.snapshot.fixed_pose + 3);
      }
      models.push_back(std::move(entry.model));
      snapshot_models.push_back(std::move(entry.snapshot));
    }
    model_states_->setModels(std::move(models), bus);
    world_snapshot_->setModels(std::move(snapshot_models), world_loop_->steps());
  });
}

bool Node::worldFrame(WorldSnapshot::Frame& out) {
  if (!world_loop_ || !world_snapshot_) return false;
  if (!world_snapshot_->enabled()) {
    world_snapshot_->enable();
    // The first frame at once, not at the next snapshot of world time.
    if (started_) world_loop_->whilePaused([&] { world_snapshot_->take(world_loop_->steps()); });
  } else if (world_loop_->paused() && started_) {
    // A paused world takes no snapshot of its own; what changed it while
    // paused (a step, a reset, a model moved) shows now.
    world_loop_->whilePaused([&] { world_snapshot_->take(world_loop_->steps()); });
  }
  world_snapshot_->read(out);
  return true;
}

ModelState Node::modelState(const std::string& model) {
  RobotInstance* robot = findModel(model);
  if (robot == nullptr) {
    throw Error(fmt::format("no model '{}' in this world (it has: {})", model, modelNames(robotNamespaces())));
  }
  ModelState state;
  state.name = robot->robotName();
  state.ns = robot->robotNamespace();
  auto* simulated = dynamic_cast<hardware_interface::SimulatedRobotHW*>(&robot->hardware());
  hardware_interface::BaseGroundTruth base;
  if (simulated != nullptr && simulated->readBaseGroundTruth(base)) {
    std::copy(std::begin(base.position), std::end(base.position), state.position);
    std::copy(std::begin(base.orientation), std::end(base.orientation), state.orientation);
    std::copy(std::begin(base.linear_velocity), std::end(base.linear_velocity), state.linear_velocity);
    std::copy(std::begin(base.angular_velocity), std::end(base.angular_velocity), state.angular_velocity);
    return state;
  }
  // A fixed base stays where it was spawned.
  state.fixed = true;
  spawnPose(parameters_, state.ns, state.position, state.orientation);
  return state;
}

void Node::setModelConfiguration(const std::string& model, const std::vector<std::string>& joints,
                                 const std::vector<double>& positions) {
  RobotInstance* robot = findModel(model);
  if (robot == nullptr) {
    throw Error(fmt::format("set_model_configuration: no model '{}' in this world (it has: {})", model,
                            modelNames(robotNamespaces())));
  }
  auto* simulated = dynamic_cast<hardware_interface::SimulatedRobotHW*>(&robot->hardware());
  if (simulated == nullptr || robot->wallClock()) {
    throw Error(fmt::format("set_model_configuration: robot '{}' runs on hardware (or the wall clock); its joints "
                            "cannot be moved by the world",
                            robot->robotNamespace()));
  }
  world::WorldLoop& loop = requireWorldLoop("set_model_configuration");
  loop.whilePaused([&] { simulated->setJointPositions(joints, positions); });
}

void Node::setModelState(const std::string& model, const std::optional<ModelPose>& pose,
                         const std::optional<ModelTwist>& twist) {
  RobotInstance* robot = findModel(model);
  if (robot == nullptr) {
    throw Error(fmt::format("set_model_state: no model '{}' in this world (it has: {})", model,
                            modelNames(robotNamespaces())));
  }
  auto* simulated = dynamic_cast<hardware_interface::SimulatedRobotHW*>(&robot->hardware());
  if (simulated == nullptr || robot->wallClock()) {
    throw Error(fmt::format("set_model_state: robot '{}' runs on hardware (or the wall clock); the world cannot move it",
                            robot->robotNamespace()));
  }
  world::WorldLoop& loop = requireWorldLoop("set_model_state");
  loop.whilePaused([&] {
    hardware_interface::BaseGroundTruth state;
    if (!simulated->readBaseGroundTruth(state)) {
      throw Error(fmt::format("set_model_state: model '{}' ({}) has a fixed base, welded to the world at its spawn "
                              "pose; only a floating base can be moved (give it another sim/pose and reset the "
                              "world, or spawn it elsewhere)",
                              robot->robotName(), robot->robotNamespace()));
    }
    if (pose) {
      std::copy(std::begin(pose->position), std::end(pose->position), state.position);
      std::copy(std::begin(pose->orientation), std::end(pose->orientation), state.orientation);
    }
    if (twist) {
      std::copy(std::begin(twist->linear), std::end(twist->linear), state.linear_velocity);
      std::copy(std::begin(twist->angular), std::end(twist->angular), state.angular_velocity);
    }
    try {
      simulated->setBaseState(state);
    } catch (const Error& e) {
      throw Error(fmt::format("set_model_state: model '{}': {}", robot->robotName(), e.what()));
    }
  });
}

std::string Node::deleteModel(const std::string& model) {
  std::unique_ptr<RobotInstance> robot;
  std::unique_ptr<NodeOperations> operations;
  std::unique_ptr<ipc::IpcServer> server;
  std::vector<std::unique_ptr<TopicRecorder>> recordings;
  {
    std::lock_guard lock(robots_mutex_);
    if (!accepting_robots_) throw Error("delete_model: the node is shutting down");
    const std::string ns = model.empty() || model.front() == '/' ? model : "/" + model;
    auto it = std::find_if(robots_.begin(), robots_.end(), [&](const auto& r) { return r->robotNamespace() == ns; });
    if (it == robots_.end()) {
      it = std::find_if(robots_.begin(), robots_.end(), [&](const auto& r) { return r->robotName() == model; });
    }
    if (it == robots_.end()) {
      std::vector<std::string> names;
      for (const auto& r : robots_) names.push_back(r->robotNamespace());
      throw Error(fmt::format("delete_model: no model '{}' in this world (it has: {})", model, modelNames(names)));
    }
    robot = std::move(*it);
    robots_.erase(it);
    for (std::size_t i = 0; i < operations_.size(); ++i) {
      if (operations_[i]->robot() == robot.get()) {
        operations = std::move(operations_[i]);
        server = std::move(servers_[i]);
        operations_.erase(operations_.begin() + static_cast<std::ptrdiff_t>(i));
        servers_.erase(servers_.begin() + static_cast<std::ptrdiff_t>(i));
        break;
      }
    }
    for (auto r = recorders_.begin(); r != recorders_.end();) {
      if (&(*r)->bus() == &robot->topics()) {
        recordings.push_back(std::move(*r));
        r = recorders_.erase(r);
      } else {
        ++r;
      }
    }
  }
  // Off /gazebo/model_states (and off its bus, if it carried the topic) first.
  refreshModelStates();
  const std::string ns = robot->robotNamespace();
  std::string running;
  for (const controller_manager::ControllerSpec& controller : robot->manager().listControllers()) {
    if (controller.state == controller_manager::ControllerState::running) {
      running += (running.empty() ? "" : ", ") + controller.name;
    }
  }
  logger().info("deleting model '{}' ({}){}", robot->robotName(), ns,
                running.empty() ? std::string() : "; stopping its running controllers first: " + running);
  // Out of the loop first: no cycle of it runs from here on.
  robot->stop();
  robot->topics().flush();
  for (auto& recording : recordings) recording->close();
  robot->shutdownControllers();
  {
    std::lock_guard names(namespaces_mutex_);
    namespaces_.erase(ns);
  }
  // The socket stops before the robot it serves goes; its bodies leave the
  // world between two cycles.
  auto finish = [this, robot = std::move(robot), operations = std::move(operations),
                 server = std::move(server)]() mutable {
    if (server) server->stop();
    operations.reset();
    server.reset();
    changeWorld([&] { robot.reset(); });
  };
  if (operations && NodeOperations::servingOnThisThread() == operations.get()) {
    std::lock_guard lock(robots_mutex_);
    model_reapers_.emplace_back(std::move(finish));
  } else {
    finish();
  }
  logger().info("deleted model {}", ns);
  return ns;
}

WorldState Node::worldState() const {
  WorldState state;
  state.sim_time_s = simTime();
  if (world_loop_) {
    state.paused = world_loop_->paused();
    state.steps = world_loop_->steps();
  }
  return state;
}

void Node::changeWorld(const std::function<void()>& change) {
  if (world_loop_ && world_->robotsTouch()) {
    world_loop_->whilePaused(change);
  } else {
    change();
  }
}

Node::~Node() {
  try {
    shutdown();
  } catch (const std::exception& e) {
    logger().error("shutting the node down failed: {}", e.what());
  }
  // Whatever shutdown() did not get to: nothing steps the world while the
  // robots built into it are destroyed.
  if (world_loop_) world_loop_->stop();
}

RobotInstance* Node::robotForTopic(const std::string& topic) {
  std::lock_guard lock(robots_mutex_);
  RobotInstance* best = nullptr;
  std::size_t best_length = 0;
  for (const auto& robot : robots_) {
    const std::string& ns = robot->robotNamespace();
    if (topicUnder(topic, ns) && (best == nullptr || ns.size() > best_length)) {
      best = robot.get();
      best_length = ns.size();
    }
  }
  // A topic outside every robot namespace goes to the first robot's bus.
  if (best == nullptr && !robots_.empty()) best = robots_.front().get();
  return best;
}

std::string Node::spawnRobot(const RobotSpec& spec) {
  // Model names are unique, as in Gazebo: the model services find a model by it.
  if (!spec.model.empty()) {
    std::lock_guard lock(robots_mutex_);
    for (const auto& robot : robots_) {
      if (robot->robotName() == spec.model) {
        throw Error(fmt::format("a model named '{}' exists already (namespace {}); give the new one another model name",
                                spec.model, robot->robotNamespace()));
      }
    }
  }
  for (const auto& parameters : spec.params) {
    if (parameters.file.empty()) {
      parameters_.loadString(parameters.yaml, parameters.source_name, parameters.ns);
    } else {
      parameters_.loadFile(parameters.file.string(), parameters.ns);
    }
  }
  for (const auto& [name, value] : options_.parameter_overrides) parameters_.setNode(name, value);
  RobotWorld world;
  world.plugins = plugins_;
  world.parameters = &parameters_;
  world.world = launch_.world;
  world.update_rate_hz = launch_.controller_manager.update_rate_hz;
  world.real_time_factor = real_time_factor_;
  world.realtime = launch_.realtime;
  world.simulated_world = world_;
  world.world_loop = world_loop_.get();
  std::unique_ptr<RobotInstance> robot;
  bool running = false;
  {
    std::lock_guard lock(robots_mutex_);
    running = started_;
  }
  // The namespace is taken while the world stands, so that a robot refused
  // for it never moves in the world.
  changeWorld([&] {
    robot = std::make_unique<RobotInstance>(spec, world);
    // A robot spawned into a running node gets a socket of its own: its
    // namespace must be one that socket can have (a launch file's robots
    // share the node's, as they start with it).
    if (running) {
      if (const std::string problem = spawnNamespaceProblem(robot->robotNamespace()); !problem.empty()) {
        const std::string ns = robot->robotNamespace();
        robot.reset();
        throw ConfigError(fmt::format("robot namespace '{}' {}", ns, problem));
      }
    }
    std::lock_guard names(namespaces_mutex_);
    if (!namespaces_.insert(robot->robotNamespace()).second) {
      const std::string ns = robot->robotNamespace();
      robot.reset();
      throw Error(fmt::format("a robot with namespace '{}' exists already; give the new one another --namespace", ns));
    }
  });
  // A robot that cannot be added leaves the world as it came (between two cycles).
  const auto discard = [&] {
    {
      std::lock_guard names(namespaces_mutex_);
      namespaces_.erase(robot->robotNamespace());
    }
    changeWorld([&] { robot.reset(); });
  };
  robot->setFinishedCallback([this] {
    {
      std::lock_guard lock(finished_mutex_);
      robot_finished_ = true;
    }
    finished_wake_.notify_all();
  });
  const std::string ns = robot->robotNamespace();

  std::unique_lock lock(robots_mutex_);
  const auto refuse = [&](const std::string& why) {
    lock.unlock();
    discard();
    throw Error(why);
  };
  if (!accepting_robots_) refuse("the node is shutting down; no robot can be spawned any more");
  logger().info("spawned robot '{}' ({}) from {} on the {} backend", robot->robotName(), ns, spec.urdf.string(),
                robot->backendName());
  RobotInstance& added = *robots_.emplace_back(std::move(robot));
  if (started_) {
    try {
      startRobotLocked(added);
    } catch (...) {
      // A robot whose loop or socket did not start is taken down whole: out of
      // the list, its loop stopped (it leaves the world loop), its namespace
      // free again and its bodies out of the world, so that nothing is left
      // running that no one can reach.
      robot = std::move(robots_.back());
      robots_.pop_back();
      lock.unlock();
      robot->stop();
      discard();
      throw;
    }
  }
  lock.unlock();
  refreshModelStates();
  return ns;
}

void Node::startServer(const std::string& socket_namespace, RobotInstance* robot) {
  auto operations = std::make_unique<NodeOperations>(*this, robot, socket_namespace);
  NodeOperations* handler = operations.get();
  auto server = std::make_unique<ipc::IpcServer>(
      ipc::socketPathFor(socket_namespace),
      [handler](const nlohmann::json& request, ipc::IpcConnection& connection) { return handler->handle(request, connection); });
  server->start();
  logger().info("serving {} on {}", socket_namespace, server->socketPath().string());
  operations_.push_back(std::move(operations));
  servers_.push_back(std::move(server));
}

void Node::startRobotLocked(RobotInstance& robot) {
  // The socket opens once the launch file's controllers run (start() waits for them).
  robot.start(options_.duration_s);
  if (options_.serve_ipc) startServer(robot.robotNamespace(), &robot);
}

void Node::start() {
  std::lock_guard lock(robots_mutex_);
  if (started_) return;
  started_ = true;
  start_time_ = std::chrono::steady_clock::now();
  // The world's own socket (default.sock), for the world and model commands
  // of a world with several robots. A node with robots leaves it to another
  // node that holds it already; without a robot it is the node's only socket.
  const bool root_robot = std::any_of(robots_.begin(), robots_.end(),
                                      [](const auto& robot) { return robot->robotNamespace() == "/"; });
  if (options_.serve_ipc && robots_.empty()) {
    startServer("/", nullptr);
  } else if (options_.serve_ipc && !root_robot) {
    try {
      startServer("/", nullptr);
    } catch (const Error& e) {
      logger().info("the world socket is served by another node ({}); this world is reached through its robots' "
                    "sockets",
                    e.what());
    }
  }
  // The world's robots join its loop before it runs, so all of them enter
  // (their launch controllers start) before the world's first physics step;
  // robots on the wall clock start their own threads.
  for (const auto& robot : robots_) robot->start(options_.duration_s);
  if (world_loop_) {
    // A new world steps as a reset one does (SimulatedWorld::restart).
    world_->restart();
    world_loop_->start();
  }
  if (options_.serve_ipc) {
    for (const auto& robot : robots_) startServer(robot->robotNamespace(), robot.get());
  }
}

void Node::waitUntilDone(const std::function<void()>& tick, std::chrono::milliseconds tick_period) {
  while (!shutdownRequested()) {
    bool all_finished = true;
    bool any_robot = false;
    const auto now = std::chrono::steady_clock::now();
    for (RobotInstance* robot : robots()) {
      any_robot = true;
      robot->watchHardware(now);
      robot->manager().processFaults();
      robot->loop().logHardwareErrorReport();
      robot->publishDiagnosticsIfDue();
      robot->logHardwareEmergencyStops();
      all_finished &= robot->finished();
    }
    if (tick) tick();
    if (options_.duration_s && (all_finished || !any_robot)) break;
    if (!options_.duration_s && any_robot && all_finished) {
      logger().warn("every robot's control loop has stopped (the hardware asked to stop); ending the run");
      break;
    }
    // Until the next tick, or at once when a robot's loop ends (a short run
    // is not kept waiting for the tick; a shutdown request from a signal
    // handler is seen at the next tick).
    std::unique_lock lock(finished_mutex_);
    finished_wake_.wait_for(lock, tick_period, [this] { return robot_finished_; });
    robot_finished_ = false;
  }
}

RunSummary Node::summary() {
  if (final_summary_) return *final_summary_;
  RunSummary summary;
  summary.wall_time_s =
      started_ ? std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time_).count() : 0.0;
  for (RobotInstance* robot : robots()) {
    RobotSummary part = summarizeRobot(*robot);
    summary.sim_time_s = std::max(summary.sim_time_s, robot->simTime());
    summary.cycles += part.loop.cycles;
    summary.robots.push_back(std::move(part));
  }
  summary.real_time_factor = summary.wall_time_s > 0.0 ? summary.sim_time_s / summary.wall_time_s : 0.0;
  return summary;
}

void Node::shutdown() {
  if (shut_down_) return;
  shut_down_ = true;
  {
    // From here on servers_ and operations_ no longer grow.
    std::lock_guard lock(robots_mutex_);
    accepting_robots_ = false;
  }
  // Robots deleted over their own socket finish leaving.
  std::vector<std::thread> reapers;
  {
    std::lock_guard lock(robots_mutex_);
    reapers.swap(model_reapers_);
  }
  for (std::thread& reaper : reapers) {
    if (reaper.joinable()) reaper.join();
  }
  // No new requests while the world is taken down; open streams end here,
  // and a `world.step` still running ends now.
  for (auto& server : servers_) server->stop();
  if (world_loop_) world_loop_->cancelSteps();
  operations_.clear();
  for (RobotInstance* robot : robots()) robot->stop();
  if (world_loop_) world_loop_->stop();
  final_summary_ = summary();
  for (RobotInstance* robot : robots()) {
    robot->topics().flush();
    robot->manager().processFaults();
    robot->loop().logHardwareErrorReport();
  }
  for (auto& recorder : recorders_) recorder->close();
  for (RobotInstance* robot : robots()) {
    // An abandoned robot's thread may still come back into its controllers.
    if (!robot->abandoned()) robot->shutdownControllers();
  }
  recorders_.clear();
  servers_.clear();
  // A deletion that began before the shutdown did.
  {
    std::lock_guard lock(robots_mutex_);
    reapers.swap(model_reapers_);
  }
  for (std::thread& reaper : reapers) {
    if (reaper.joinable()) reaper.join();
  }
  std::lock_guard lock(robots_mutex_);
  // A robot whose loop thread was left inside a hardware call that never
  // returned stays alive (unused) until the process ends: that thread may
  // still come back to it.
  for (auto& robot : robots_) {
    if (robot->abandoned()) static_cast<void>(robot.release());
  }
  robots_.clear();
}

RobotInstance* Node::findRobot(const std::string& robot_namespace) {
  std::lock_guard lock(robots_mutex_);
  for (const auto& robot : robots_) {
    if (robot->robotNamespace() == robot_namespace) return robot.get();
  }
  return nullptr;
}

std::vector<std::string> Node::robotNamespaces() const {
  std::lock_guard lock(robots_mutex_);
  std::vector<std::string> names;
  for (const auto& robot : robots_) names.push_back(robot->robotNamespace());
  return names;
}

std::vector<RobotInstance*> Node::robots() const {
  std::lock_guard lock(robots_mutex_);
  std::vector<RobotInstance*> list;
  for (const auto& robot : robots_) list.push_back(robot.get());
  return list;
}

double Node::simTime() const {
  double time = 0.0;
  for (RobotInstance* robot : robots()) time = std::max(time, robot->simTime());
  return time;
}

}  // namespace servoloop::node
