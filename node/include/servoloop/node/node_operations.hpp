#pragma once
// The request handler behind one IPC socket of a node: every operation of
// docs/node_operations.md, acting on the socket's robot (or, on the world's
// default.sock, on the only robot if there is exactly one). Non-real-time.
//
// Operations that wait for a robot's loop (control.load, control.unload,
// control.switch, control.reload_libraries) run on this object's worker
// thread and reply when done, so the socket's service thread keeps serving
// other clients (and `topic echo` streams) meanwhile.
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <utility>

#include <nlohmann/json.hpp>

#include "servoloop/ipc/ipc_connection.hpp"
#include "servoloop/realtime/action_registry.hpp"
#include "servoloop/realtime/topic_subscription.hpp"

namespace servoloop::node {

class Node;
struct ModelState;
class RobotInstance;

// A model's state as model.get replies it (and the Python package gives it):
// name, namespace, fixed, pose {position, orientation}, twist {linear, angular}.
nlohmann::json modelStateToJson(const ModelState& state);
// model.set_state: `request` {model, pose?, twist?} (the JSON form of
// modelStateToJson) read and carried out by Node::setModelState; returns the
// model's new state. Throws servoloop::Error naming a missing or bad field.
nlohmann::json setModelStateFromJson(Node& node, const nlohmann::json& request);

class NodeOperations {
 public:
  // robot: the socket's robot; nullptr for the world socket.
  NodeOperations(Node& node, RobotInstance* robot, std::string socket_namespace);
  // Drops every stream subscription and joins the worker (after the job in
  // progress). The IPC server using handle() must be stopped before.
  ~NodeOperations();
  NodeOperations(const NodeOperations&) = delete;
  NodeOperations& operator=(const NodeOperations&) = delete;

  // The IpcServer::Handler.
  nlohmann::json handle(const nlohmann::json& request, ipc::IpcConnection& connection);

  // The socket's robot (nullptr for the world socket).
  RobotInstance* robot() const noexcept { return robot_; }
  // The operations whose request or deferred job the calling thread serves
  // now, or nullptr (a thread that serves none).
  static const NodeOperations* servingOnThisThread() noexcept;

 private:
  using Job = std::function<void()>;

  // The socket's robot; on the world's socket, the robot named by the
  // request's "robot" field (namespace or model name), or the only one.
  RobotInstance& robotFor(const std::string& op, const nlohmann::json& request);
  nlohmann::json worldOp(const std::string& op, const nlohmann::json& request, ipc::IpcConnection& connection);
  nlohmann::json worldState();
  nlohmann::json deferToWorker(const nlohmann::json& request, ipc::IpcConnection& connection,
                               std::function<nlohmann::json()> work);
  void workerLoop();

  nlohmann::json ping();
  nlohmann::json controlList(RobotInstance& robot);
  nlohmann::json controlListTypes();
  nlohmann::json controlListJoints(RobotInstance& robot);
  static nlohmann::json controlSafety(RobotInstance& robot);
  static nlohmann::json controlStats(RobotInstance& robot, bool reset);
  // control.gains: gains_operations.cpp.
  nlohmann::json controlGains(RobotInstance& robot, const nlohmann::json& request);
  nlohmann::json paramOp(const std::string& op, const nlohmann::json& request);
  nlohmann::json topicList(RobotInstance& robot);
  nlohmann::json topicPub(RobotInstance& robot, const nlohmann::json& request);
  nlohmann::json topicSubscribe(RobotInstance& robot, const nlohmann::json& request, ipc::IpcConnection& connection);
  nlohmann::json topicUnsubscribe(const nlohmann::json& request, ipc::IpcConnection& connection);
  // model.*: model_operations.cpp.
  nlohmann::json modelOp(const std::string& op, const nlohmann::json& request, ipc::IpcConnection& connection);
  nlohmann::json modelSpawn(const nlohmann::json& request);
  // view.*: view_operations.cpp.
  nlohmann::json viewOp(const std::string& op);
  nlohmann::json actionList(RobotInstance& robot);
  nlohmann::json actionSend(RobotInstance& robot, const nlohmann::json& request, ipc::IpcConnection& connection);
  nlohmann::json actionStatus(const nlohmann::json& request, ipc::IpcConnection& connection);
  nlohmann::json actionCancel(const nlohmann::json& request, ipc::IpcConnection& connection);

  Node& node_;
  RobotInstance* robot_;
  std::string socket_namespace_;

  std::mutex subscriptions_mutex_;
  std::map<std::pair<std::uint64_t, std::string>, realtime::Subscription> subscriptions_;  // (connection, topic)
  std::set<std::uint64_t> watched_connections_;  // onClose registered

  // Goals sent over this socket, by id, until their sender saw them end or
  // went away (the goals themselves run on).
  struct TrackedGoal {
    std::uint64_t connection = 0;
    std::string type;
    std::shared_ptr<realtime::ActionGoal> goal;
  };
  std::mutex goals_mutex_;
  std::map<std::uint64_t, TrackedGoal> goals_;
  std::uint64_t next_goal_id_ = 1;
  std::set<std::uint64_t> goal_connections_;  // onClose registered

  std::mutex jobs_mutex_;
  std::condition_variable jobs_changed_;
  std::deque<Job> jobs_;
  bool stopping_ = false;
  std::thread worker_;
};

}  // namespace servoloop::node
