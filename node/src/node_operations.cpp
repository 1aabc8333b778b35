// The operations a node serves over IPC (docs/node_operations.md).
#include "servoloop/node/node_operations.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>

#include <filesystem>
#include <limits>
#include <thread>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "servoloop/ipc/ipc_protocol.hpp"
#include "servoloop/node/action_json.hpp"
#include "servoloop/node/message_json.hpp"
#include "servoloop/node/node.hpp"
#include "request_fields.hpp"
#include "servoloop/node/robot_namespace.hpp"
#include "servoloop/node/run_summary.hpp"
#include "servoloop/params/parameter_store.hpp"
#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::node {
namespace {

// Topics a robot's bus may hold; `topic pub` to a new name past this is refused.
constexpr std::size_t kMaxTopicsPerRobot = 4096;
// Goals one socket tracks at once; `action.send` past this is refused.
constexpr std::size_t kMaxTrackedGoals = 1024;

using nlohmann::json;

// A switch whose request says "timeout: 0" (wait forever) waits this long at
// most, so a node shutting down never waits on a loop that has stopped.
constexpr double kMaxSwitchWait_s = 10.0;
// One `world.step` runs at most this many physics steps (over 11 days at 1 ms).
constexpr std::uint64_t kMaxWorldSteps = 1'000'000'000;

std::string requireString(const json& request, const char* field) { return ipc::requireRequestString(request, field); }

std::string optionalString(const json& request, const char* field, const std::string& fallback) {
  return ipc::requestString(request, field, fallback);
}

}  // namespace

std::vector<std::string> stringList(const json& request, const char* field) {
  std::vector<std::string> values;
  const auto it = request.find(field);
  if (it == request.end() || it->is_null()) return values;
  if (!it->is_array()) ipc::throwBadRequestField(request, field, "a list of names", *it);
  for (std::size_t i = 0; i < it->size(); ++i) {
    const json& value = (*it)[i];
    if (!value.is_string()) {
      ipc::throwBadRequestField(request, std::string(field) + "[" + std::to_string(i) + "]", "a name (a string)", value);
    }
    values.push_back(value.get<std::string>());
  }
  return values;
}

NodeOperations::NodeOperations(Node& node, RobotInstance* robot, std::string socket_namespace)
    : node_(node), robot_(robot), socket_namespace_(std::move(socket_namespace)) {
  worker_ = std::thread([this] { workerLoop(); });
}

NodeOperations::~NodeOperations() {
  {
    std::lock_guard lock(jobs_mutex_);
    stopping_ = true;
  }
  jobs_changed_.notify_all();
  if (worker_.joinable()) worker_.join();
  std::map<std::pair<std::uint64_t, std::string>, realtime::Subscription> subscriptions;
  {
    std::lock_guard lock(subscriptions_mutex_);
    subscriptions.swap(subscriptions_);
  }
  subscriptions.clear();  // unsubscribes, outside the lock
}

namespace {
// The operations object whose request (or deferred job) this thread serves.
thread_local const NodeOperations* t_serving = nullptr;

struct ServingScope {
  explicit ServingScope(const NodeOperations* operations) : previous(t_serving) { t_serving = operations; }
  ~ServingScope() { t_serving = previous; }
  ServingScope(const ServingScope&) = delete;
  ServingScope& operator=(const ServingScope&) = delete;
  const NodeOperations* previous;
};
}  // namespace

const NodeOperations* NodeOperations::servingOnThisThread() noexcept { return t_serving; }

void NodeOperations::workerLoop() {
  const ServingScope serving(this);
  while (true) {
    Job job;
    {
      std::unique_lock lock(jobs_mutex_);
      jobs_changed_.wait(lock, [this] { return stopping_ || !jobs_.empty(); });
      if (jobs_.empty()) return;  // stopping, nothing left
      job = std::move(jobs_.front());
      jobs_.pop_front();
    }
    job();
  }
}

json NodeOperations::deferToWorker(const json& request, ipc::IpcConnection& connection, std::function<json()> work) {
  const json id = request.contains("id") ? request["id"] : json();
  std::weak_ptr<ipc::IpcConnection> weak = connection.shared();
  {
    std::lock_guard lock(jobs_mutex_);
    const json request_op = {{"op", ipc::requestOpName(request)}};
    jobs_.push_back([id, weak, request_op, work = std::move(work)] {
      json reply;
      try {
        reply = ipc::makeIpcOkReply(id, work());
      } catch (const nlohmann::json::exception& e) {
        reply = ipc::makeIpcErrorReply(id, ipc::describeJsonException(request_op, e));
      } catch (const std::exception& e) {
        reply = ipc::makeIpcErrorReply(id, e.what());
      }
      if (auto connection = weak.lock()) connection->sendDeferredReply(reply);
    });
  }
  jobs_changed_.notify_one();
  return ipc::IpcServer::deferredReply();
}

RobotInstance& NodeOperations::robotFor(const std::string& op, const json& request) {
  if (robot_ != nullptr) return *robot_;
  if (const json* named = ipc::findRequestField(request, "robot"); named != nullptr) {
    if (!named->is_string()) ipc::throwBadRequestField(request, "robot", "a robot's namespace or model name", *named);
    RobotInstance* robot = node_.findModel(named->get<std::string>());
    if (robot == nullptr) {
      std::string names;
      for (const RobotInstance* each : node_.robots()) names += (names.empty() ? "" : ", ") + each->robotNamespace();
      throw Error(fmt::format("'{}': no robot '{}' in this world (it has: {})", op, named->get<std::string>(),
                              names.empty() ? "none" : names));
    }
    return *robot;
  }
  const std::vector<RobotInstance*> robots = node_.robots();
  if (robots.size() == 1) return *robots.front();
  if (robots.empty()) {
    throw Error(fmt::format("'{}': this world has no robot yet; add one with `servoloop spawn-model --urdf FILE "
                            "--model NAME`",
                            op));
  }
  std::string names;
  for (const RobotInstance* robot : robots) names += (names.empty() ? "" : ", ") + robot->robotNamespace();
  throw Error(fmt::format("'{}': this world has several robots ({}); ask the robot's own socket with --namespace", op,
                          names));
}

json NodeOperations::handle(const json& request, ipc::IpcConnection& connection) {
  const ServingScope serving(this);
  const std::string op = ipc::requestOpName(request);
  if (op == "ping") return ping();
  if (op == "world.shutdown") {
    logger().info("shutdown requested over IPC");
    node_.requestShutdown();
    return nullptr;
  }
  if (op.starts_with("world.")) return worldOp(op, request, connection);
  if (op.starts_with("model.")) return modelOp(op, request, connection);
  if (op.starts_with("view.")) return viewOp(op);
  if (op.starts_with("param.")) return paramOp(op, request);
  if (op == "control.list_types") return controlListTypes();

  RobotInstance& robot = robotFor(op, request);
  if (op == "robot.description") {
    return {{"urdf", robot.robotDescription()}, {"path", robot.urdfPath().string()}, {"model", robot.robotName()}};
  }
  if (op == "control.list") return controlList(robot);
  if (op == "control.list_joints") return controlListJoints(robot);
  if (op == "control.gains") return controlGains(robot, request);
  // What waits for a cycle of the robot is refused at once while a hardware
  // call of its loop does not return.
  if (op == "control.load" || op == "control.unload" || op == "control.switch" || op == "control.recover" ||
      op == "control.reload_libraries") {
    if (const std::string stuck = robot.stuckReason(); !stuck.empty()) {
      throw Error(fmt::format("robot '{}': {}; '{}' needs a cycle of the robot and cannot be carried out until it "
                              "returns",
                              robot.robotNamespace(), stuck, op));
    }
  }
  if (op == "control.load" || op == "control.unload") {
    const std::string name = requireString(request, "name");
    const bool load = op == "control.load";
    return deferToWorker(request, connection, [&robot, name, load] {
      throwIfFailed(load ? robot.loadController(name) : robot.manager().unloadController(name));
      return json(nullptr);
    });
  }
  if (op == "control.switch") {
    controller_manager::SwitchRequest switch_request;
    switch_request.start_controllers = stringList(request, "start");
    switch_request.stop_controllers = stringList(request, "stop");
    const std::string strictness = optionalString(request, "strictness", "strict");
    if (strictness == "strict" || strictness == "STRICT" || strictness == "2") {
      switch_request.strictness = controller_manager::SwitchStrictness::STRICT;
    } else if (strictness == "best_effort" || strictness == "BEST_EFFORT" || strictness == "1") {
      switch_request.strictness = controller_manager::SwitchStrictness::BEST_EFFORT;
    } else {
      throw Error("'control.switch': strictness '" + strictness + "' must be \"strict\" or \"best_effort\"");
    }
    switch_request.start_asap = ipc::requestBool(request, "start_asap", false);
    const double timeout_s = ipc::requestNumber(request, "timeout", 0.0, "a number of seconds");
    switch_request.timeout_s = timeout_s > 0.0 ? timeout_s : kMaxSwitchWait_s;
    return deferToWorker(request, connection, [&robot, switch_request] {
      if (robot.finished()) {
        throw Error("robot '" + robot.robotNamespace() + "': its control loop has ended, so no switch can be carried out");
      }
      // The loop stands in a fault: nothing would carry a switch out. (Starts
      // under a protective stop are refused inside the switch: RobotInstance::switchRefusal.)
      if (robot.safety().state() == controller_manager::SafetyState::fault) {
        throw Error("robot '" + robot.robotNamespace() + "': " + robot.safety().reason() +
                    "; no switch can be carried out until then");
      }
      throwIfFailed(robot.manager().switchController(switch_request));
      return json(nullptr);
    });
  }
  if (op == "control.reload_libraries") {
    const bool force_kill = ipc::requestBool(request, "force_kill", false);
    return deferToWorker(request, connection, [&robot, force_kill] {
      throwIfFailed(robot.manager().reloadControllerLibraries(force_kill));
      return json(nullptr);
    });
  }
  if (op == "control.safety") return controlSafety(robot);
  if (op == "control.stats") return controlStats(robot, ipc::requestBool(request, "reset", false));
  if (op == "control.estop") {
    if (ipc::findRequestField(request, "engage") == nullptr) {
      throw Error("control.estop: 'engage' is required: true (engage the emergency stop) or false (release it)");
    }
    const bool engage = ipc::requestBool(request, "engage", false);
    throwIfFailed(robot.setEmergencyStop(engage, controller_manager::EmergencyStopSource::command));
    return controlSafety(robot);
  }
  if (op == "control.recover") {
    return deferToWorker(request, connection, [&robot] {
      throwIfFailed(robot.recover());
      return controlSafety(robot);
    });
  }
  if (op == "topic.list") return topicList(robot);
  if (op == "topic.pub") return topicPub(robot, request);
  if (op == "topic.subscribe") return topicSubscribe(robot, request, connection);
  if (op == "topic.unsubscribe") return topicUnsubscribe(request, connection);
  if (op == "action.list") return actionList(robot);
  if (op == "action.send") return actionSend(robot, request, connection);
  if (op == "action.status") return actionStatus(request, connection);
  if (op == "action.cancel") return actionCancel(request, connection);
  throw Error("unknown op '" + op +
              "'; this node serves ping, control.{list,list_types,list_joints,load,unload,switch,reload_libraries,"
              "safety,estop,recover,stats,gains}, "
              "param.{get,set,load,dump,list}, topic.{list,pub,subscribe,unsubscribe}, "
              "action.{list,send,status,cancel}, model.{list,get,spawn,set_configuration,set_state,delete}, world.{state,pause,unpause,step,reset,shutdown}");
}

json NodeOperations::worldState() {
  const WorldState state = node_.worldState();
  return {{"paused", state.paused}, {"steps", state.steps}, {"sim_time", state.sim_time_s}};
}

json NodeOperations::worldOp(const std::string& op, const json& request, ipc::IpcConnection& connection) {
  if (op == "world.state") return worldState();
  if (op == "world.pause") {
    node_.pauseWorld();
    return worldState();
  }
  if (op == "world.unpause") {
    node_.unpauseWorld();
    return worldState();
  }
  if (op == "world.step") {
    std::uint64_t steps = 1;
    if (const json* given = ipc::findRequestField(request, "steps"); given != nullptr) {
      if (!given->is_number_unsigned() || given->get<std::uint64_t>() < 1 || given->get<std::uint64_t>() > kMaxWorldSteps) {
        ipc::throwBadRequestField(request, "steps", fmt::format("a whole number from 1 to {}", kMaxWorldSteps), *given);
      }
      steps = given->get<std::uint64_t>();
    }
    return deferToWorker(request, connection, [this, steps] {
      const std::uint64_t stepped = node_.stepWorld(steps);
      json reply = worldState();
      reply["stepped"] = stepped;
      return reply;
    });
  }
  if (op == "world.reset") {
    return deferToWorker(request, connection, [this] {
      const std::string failures = node_.resetWorld();
      if (!failures.empty()) throw Error("the world was reset, but " + failures);
      return worldState();
    });
  }
  throw Error("unknown op '" + op + "'; the world serves world.{state,pause,unpause,step,reset,shutdown}");
}

json NodeOperations::ping() {
  json reply = {{"namespace", socket_namespace_}, {"sim_time", robot_ ? robot_->simTime() : node_.simTime()},
                {"robots", node_.robotNamespaces()}};
  // A robot's socket also says how its loop keeps time (for monitoring and
  // the soak test): cycles run and the cycles that overran their deadline.
  if (robot_ != nullptr) {
    const controller_manager::LoopStatisticsSnapshot loop = robot_->loop().statistics().snapshot();
    reply["loop"] = {{"cycles", loop.cycles}, {"overruns", loop.overruns}};
  }
  return reply;
}

json NodeOperations::controlStats(RobotInstance& robot, bool reset) {
  json controllers = json::array();
  for (const auto& [name, update_time] : robot.manager().updateTimes()) {
    controllers.push_back({{"name", name}, {"update", toJson(update_time)}});
  }
  json reply = {{"loop", toJson(robot.loop().statistics().snapshot())}, {"controllers", std::move(controllers)}};
  if (reset) robot.loop().requestStatisticsReset();
  return reply;
}

json NodeOperations::controlSafety(RobotInstance& robot) {
  const controller_manager::SafetySupervisor& safety = robot.safety();
  // A hardware call that does not return is a fault whatever the loop last said.
  const std::string stuck = robot.stuckReason();
  return {{"state", stuck.empty() ? controller_manager::toString(safety.state()) : "fault"},
          {"emergency_stop", safety.emergencyStopLatched()},
          {"hardware_emergency_input", safety.hardwareEmergencyInput()},
          {"reason", stuck.empty() ? safety.reason() : stuck},
          {"protective_stops", safety.protectiveStops()},
          {"emergency_stops", safety.emergencyStops()}};
}

json NodeOperations::controlList(RobotInstance& robot) {
  json controllers = json::array();
  for (const controller_manager::ControllerSpec& spec : robot.manager().listControllers()) {
    json claims = json::array();
    for (const auto& claim : spec.claimed_resources) {
      claims.push_back({{"hardware_interface", claim.hardware_interface},
                        {"resources", std::vector<std::string>(claim.resources.begin(), claim.resources.end())}});
    }
    json entry = {{"name", spec.name},
                  {"type", spec.type},
                  {"state", toString(spec.state)},
                  {"claimed_resources", std::move(claims)},
                  {"update_rate", spec.update_rate_hz}};
    if (!spec.last_fault.empty()) entry["last_fault"] = spec.last_fault;
    controllers.push_back(std::move(entry));
  }
  return {{"controllers", std::move(controllers)}};
}

json NodeOperations::controlListTypes() {
  json types = json::array();
  for (const plugin::PluginTypeInfo& info : node_.plugins().listTypes()) {
    types.push_back({{"type", info.type}, {"kind", info.kind}, {"library", info.library.string()}});
  }
  return {{"types", std::move(types)}};
}

json NodeOperations::controlListJoints(RobotInstance& robot) {
  json joints = json::array();
  for (const auto& [name, interfaces] : robot.jointInterfaces()) joints.push_back({{"name", name}, {"interfaces", interfaces}});
  return {{"joints", std::move(joints)}};
}

json NodeOperations::paramOp(const std::string& op, const json& request) {
  params::ParameterStore& store = node_.parameters();
  if (op == "param.get") {
    const std::string name = requireString(request, "name");
    return {{"value", yamlToJson(store.node(name))}};
  }
  if (op == "param.set") {
    const std::string name = requireString(request, "name");
    if (!request.contains("value")) throw Error("'param.set' needs a field 'value'");
    const json& value = request["value"];
    if (value.is_string()) {
      store.set(name, std::string_view(value.get<std::string>()));
    } else {
      // JSON is YAML (flow style), so the value keeps its JSON types.
      store.setNode(name, YAML::Load(value.dump()));
    }
    return nullptr;
  }
  if (op == "param.load") {
    const std::string ns = optionalString(request, "namespace", "/");
    if (request.contains("file")) {
      const std::string file = requireString(request, "file");
      if (!std::filesystem::path(file).is_absolute()) {
        throw Error("'param.load': file '" + file + "' must be an absolute path (the node's folder is not yours)");
      }
      store.loadFile(file, ns);
    } else {
      const std::string yaml = requireString(request, "yaml");
      store.loadString(yaml, optionalString(request, "source", "<param.load>"), ns);
    }
    return nullptr;
  }
  if (op == "param.dump") return {{"yaml", store.dump(optionalString(request, "namespace", "/"))}};
  if (op == "param.list") return {{"names", store.list(optionalString(request, "namespace", "/"))}};
  throw Error("unknown op '" + op + "'; the parameter operations are param.get, param.set, param.load, param.dump, param.list");
}

json NodeOperations::topicList(RobotInstance& robot) {
  json topics = json::array();
  for (const realtime::TopicInfo& info : robot.topics().list()) {
    topics.push_back({{"name", info.name}, {"type", info.type}, {"publishers", info.publishers},
                      {"subscribers", info.subscribers}});
  }
  return {{"topics", std::move(topics)}};
}

json NodeOperations::topicPub(RobotInstance& robot, const json& request) {
  const std::string topic = requireString(request, "topic");
  const std::string type = optionalString(request, "type", "");
  if (!request.contains("msg")) throw Error("'topic.pub' needs a field 'msg' (the message as JSON, e.g. {\"data\": 1.0})");
  // Each new topic keeps its slots for the node's lifetime: a client
  // publishing to ever new names must not grow the node without end.
  realtime::TopicBus& bus = robot.topics();
  if (!bus.hasTopic(topic) && bus.list().size() >= kMaxTopicsPerRobot) {
    throw Error("topic '" + topic + "' would be topic number " + std::to_string(kMaxTopicsPerRobot + 1) +
                " of this robot; the limit is " + std::to_string(kMaxTopicsPerRobot) +
                " (is a client publishing to generated names?)");
  }
  servoloop::node::publishJson(bus, topic, request["msg"], type);
  return nullptr;
}

json NodeOperations::topicSubscribe(RobotInstance& robot, const json& request, ipc::IpcConnection& connection) {
  const std::string topic = realtime::TopicBus::normalizeTopicName(requireString(request, "topic"));
  const std::uint64_t connection_id = connection.id();
  std::lock_guard lock(subscriptions_mutex_);
  const auto key = std::make_pair(connection_id, topic);
  if (subscriptions_.count(key) != 0) return nullptr;  // already streaming

  realtime::TopicBus& bus = robot.topics();
  std::weak_ptr<ipc::IpcConnection> weak = connection.shared();
  // The type is looked up once it is known (a topic may have no type yet).
  auto type = std::make_shared<std::string>();
  subscriptions_.emplace(key, servoloop::node::subscribeJson(bus, topic, [weak, topic, type, &bus](Time stamp, const json& msg) {
    auto target = weak.lock();
    if (!target || !target->isOpen()) return;
    if (type->empty()) *type = bus.typeOf(topic);
    target->send(ipc::makeIpcStreamMessage(topic, {{"type", *type}, {"stamp", stamp.seconds}, {"msg", msg}}));
  }));
  if (watched_connections_.insert(connection_id).second) {
    connection.onClose([this, connection_id] {
      std::vector<realtime::Subscription> dropped;
      {
        std::lock_guard inner(subscriptions_mutex_);
        watched_connections_.erase(connection_id);
        for (auto it = subscriptions_.begin(); it != subscriptions_.end();) {
          if (it->first.first == connection_id) {
            dropped.push_back(std::move(it->second));
            it = subscriptions_.erase(it);
          } else {
            ++it;
          }
        }
      }
    });
  }
  return nullptr;
}

json NodeOperations::topicUnsubscribe(const json& request, ipc::IpcConnection& connection) {
  const std::string topic = realtime::TopicBus::normalizeTopicName(requireString(request, "topic"));
  realtime::Subscription dropped;
  {
    std::lock_guard lock(subscriptions_mutex_);
    const auto it = subscriptions_.find(std::make_pair(connection.id(), topic));
    if (it == subscriptions_.end()) throw Error("'topic.unsubscribe': this connection is not subscribed to '" + topic + "'");
    dropped = std::move(it->second);
    subscriptions_.erase(it);
  }
  return nullptr;  // `dropped` unsubscribes here, outside the lock
}

json NodeOperations::actionList(RobotInstance& robot) {
  json actions = json::array();
  for (const realtime::ActionInfo& info : robot.actions().list()) {
    actions.push_back({{"name", info.name}, {"type", info.type}});
  }
  return {{"actions", std::move(actions)}};
}

namespace {
std::uint64_t requireGoalId(const json& request) {
  return ipc::requireRequestUnsigned(request, "goal_id", "the goal_id that action.send replied (a whole number)");
}
}  // namespace

json NodeOperations::actionSend(RobotInstance& robot, const json& request, ipc::IpcConnection& connection) {
  const std::string name = requireString(request, "name");
  const std::string type = optionalString(request, "type", "");
  if (!request.contains("goal")) throw Error("'action.send' needs a field 'goal' (the goal as JSON)");
  {
    std::lock_guard lock(goals_mutex_);
    if (goals_.size() >= kMaxTrackedGoals) {
      throw Error("'action.send': " + std::to_string(kMaxTrackedGoals) +
                  " goals of this socket are still followed; read their status (action.status) until they end");
    }
  }
  const std::string action_type = type.empty() ? robot.actions().typeOf(name) : type;
  std::shared_ptr<realtime::ActionGoal> goal = sendGoalJson(robot.actions(), name, action_type, request["goal"]);
  const std::uint64_t connection_id = connection.id();
  std::uint64_t id = 0;
  bool watch = false;
  {
    std::lock_guard lock(goals_mutex_);
    id = next_goal_id_++;
    goals_[id] = TrackedGoal{connection_id, action_type, goal};
    watch = goal_connections_.insert(connection_id).second;
  }
  if (watch) {
    connection.onClose([this, connection_id] {
      std::vector<std::shared_ptr<realtime::ActionGoal>> dropped;  // released outside the lock
      std::lock_guard lock(goals_mutex_);
      goal_connections_.erase(connection_id);
      for (auto it = goals_.begin(); it != goals_.end();) {
        if (it->second.connection == connection_id) {
          dropped.push_back(std::move(it->second.goal));
          it = goals_.erase(it);
        } else {
          ++it;
        }
      }
    });
  }
  return {{"goal_id", id}, {"state", realtime::goalStateName(goal->state())}};
}

json NodeOperations::actionStatus(const json& request, ipc::IpcConnection& connection) {
  const std::uint64_t id = requireGoalId(request);
  TrackedGoal tracked;
  {
    std::lock_guard lock(goals_mutex_);
    const auto it = goals_.find(id);
    if (it == goals_.end() || it->second.connection != connection.id()) {
      throw Error("'action.status': no goal " + std::to_string(id) + " of this connection (it ended and was read, "
                  "or was sent over another connection)");
    }
    tracked = it->second;
  }
  const realtime::GoalState state = tracked.goal->state();
  json reply = {{"state", realtime::goalStateName(state)}, {"feedback", feedbackJson(tracked.type, *tracked.goal)}};
  // Why it ended, as actionlib's GoalStatus text (a rejection's reason too).
  if (std::string text = tracked.goal->statusText(); !text.empty()) reply["text"] = std::move(text);
  if (realtime::goalDone(state)) {
    reply["result"] = resultJson(tracked.type, *tracked.goal);
    std::lock_guard lock(goals_mutex_);
    goals_.erase(id);
  }
  return reply;
}

json NodeOperations::actionCancel(const json& request, ipc::IpcConnection& connection) {
  const std::uint64_t id = requireGoalId(request);
  std::shared_ptr<realtime::ActionGoal> goal;
  {
    std::lock_guard lock(goals_mutex_);
    const auto it = goals_.find(id);
    if (it == goals_.end() || it->second.connection != connection.id()) {
      throw Error("'action.cancel': no goal " + std::to_string(id) + " of this connection");
    }
    goal = it->second.goal;
  }
  goal->cancel();
  return nullptr;
}

}  // namespace servoloop::node
