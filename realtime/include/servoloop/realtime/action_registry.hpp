#pragma once
// Actions (ROS's actionlib, without ROS): a controller serves an action under
// a name, e.g. /arm/arm_controller/follow_joint_trajectory of type
// control_msgs/FollowJointTrajectory; a client sends a goal, reads its
// feedback while it runs and its result when it ends, and may cancel it.
// A server has one active goal at a time unless it says otherwise: a new goal
// preempts the running one.
//
// Goals, feedback and results are the action type's structs
// (action_messages.hpp), passed as pointers next to the action type's name,
// as the topic bus passes messages. Everything here is non-real-time; a
// controller's real-time thread never waits on it (the controller hands goals
// to its loop as it hands commands).
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace servoloop::realtime {

enum class GoalState {
  pending,    // accepted, not started yet
  active,     // running
  succeeded,
  aborted,    // the server gave up (see the result)
  preempted,  // replaced by a newer goal, or stopped by its controller
  canceled,   // canceled by its sender
  rejected,   // refused before it started (see the result)
};

// "SUCCEEDED", "ABORTED", ... as actionlib names the states.
const char* goalStateName(GoalState state) noexcept;
inline bool goalDone(GoalState state) noexcept { return state != GoalState::pending && state != GoalState::active; }

// One goal as its sender sees it. Any thread.
class ActionGoal {
 public:
  virtual ~ActionGoal() = default;
  virtual GoalState state() const = 0;
  virtual void cancel() = 0;
  // The newest feedback, into the action type's Feedback struct; false when
  // there is none yet.
  virtual bool feedback(void* out) const = 0;
  // The result, into the action type's Result struct (meaningful once done).
  virtual void result(void* out) const = 0;
  // Why the goal ended as it did (actionlib's GoalStatus text): the reason a
  // goal was rejected or aborted, "" when there is nothing to say.
  virtual std::string statusText() const { return {}; }
};

// What a controller implements to serve an action.
class ActionServer {
 public:
  virtual ~ActionServer() = default;
  // Non-real-time. goal points to the action type's Goal struct. Returns the
  // goal (rejected ones too, with the reason in their result); never null.
  virtual std::shared_ptr<ActionGoal> sendGoal(const void* goal) = 0;
};

struct ActionInfo {
  std::string name;  // e.g. "/arm/arm_controller/follow_joint_trajectory"
  std::string type;  // e.g. "control_msgs/FollowJointTrajectory"
};

class ActionRegistry;

// Keeps an action served; destroying or reset()ting it withdraws the action
// (after a sendGoal in progress returns). May outlive the registry.
class ActionRegistration {
 public:
  ActionRegistration() = default;
  ActionRegistration(ActionRegistration&& other) noexcept;
  ActionRegistration& operator=(ActionRegistration&& other) noexcept;
  ActionRegistration(const ActionRegistration&) = delete;
  ActionRegistration& operator=(const ActionRegistration&) = delete;
  ~ActionRegistration() { reset(); }
  void reset();
  bool active() const noexcept { return !name_.empty(); }

 private:
  friend class ActionRegistry;
  struct Core;
  ActionRegistration(std::weak_ptr<Core> core, std::string name) : core_(std::move(core)), name_(std::move(name)) {}
  std::weak_ptr<Core> core_;
  std::string name_;
};

class ActionRegistry {
 public:
  ActionRegistry();
  ~ActionRegistry();
  ActionRegistry(const ActionRegistry&) = delete;
  ActionRegistry& operator=(const ActionRegistry&) = delete;

  // Serves server under name (a ROS name, normalised as topic names are).
  // Throws servoloop::Error when the name is taken or not a ROS name.
  [[nodiscard]] ActionRegistration add(std::string_view name, std::string_view type,
                                       std::shared_ptr<ActionServer> server);

  // Every action, sorted by name.
  std::vector<ActionInfo> list() const;
  // The type of the action `name`, "" when there is none.
  std::string typeOf(std::string_view name) const;

  // Sends goal (the type's Goal struct) to the action `name`. Throws
  // servoloop::Error naming the action and the actions there are when there
  // is no such action, or when type is not the action's type.
  std::shared_ptr<ActionGoal> sendGoal(std::string_view name, std::string_view type, const void* goal);

 private:
  std::shared_ptr<ActionRegistration::Core> core_;
};

}  // namespace servoloop::realtime
