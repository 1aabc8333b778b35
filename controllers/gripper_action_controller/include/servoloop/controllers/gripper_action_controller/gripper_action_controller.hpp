#pragma once
// position_controllers/GripperActionController and
// effort_controllers/GripperActionController: a one-joint gripper driven by
// the gripper_cmd action (control_msgs/GripperCommand), as ros_controllers'
// gripper_action_controller does, with its parameters.
//
// Parameters (under <robot ns>/<controller>):
//   joint                     required, the gripper joint
//   gains/<joint>             effort: required PID gains (p, i, d, i_clamp, antiwindup)
//   goal_tolerance            position error at which a goal succeeds (default 0.01)
//   max_effort                effort limit before the first goal (default 0: none applied)
//   stall_velocity_threshold  below this speed the gripper counts as not moving (default 0.001)
//   stall_timeout             s without moving, short of the goal, after which it stalled (default 1)
//   action_monitor_rate       Hz of goal feedback (default 20)
// Action: <robot ns>/<controller>/gripper_cmd (control_msgs/GripperCommand):
//   goal {command: {position, max_effort}}; feedback and result {position,
//   effort, stalled, reached_goal}.
// Each update: error = commanded position − position, and
//   position interface: the joint is commanded the position (effort reports max_effort);
//   effort interface:   effort = PID(error, −velocity), clamped to ±|max_effort|.
// A goal succeeds once |error| < goal_tolerance; it is aborted with stalled =
// true when the gripper has not moved faster than stall_velocity_threshold for
// stall_timeout short of it (closing on an object) — the command stays, so the
// gripper keeps squeezing with max_effort. A new goal preempts the running
// one; a cancel holds the position the gripper has; stopping the controller
// (a switch, a fault, unloading it) aborts its goal with the reason (and
// zeroes an effort command); a goal sent while it is not running is rejected
// with the reason.
// Starting: hold the current position.
#include <atomic>
#include <memory>
#include <mutex>
#include <string>

#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/controllers/common/periodic_gate.hpp"
#include "servoloop/controllers/pid.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/realtime/action_messages.hpp"
#include "servoloop/realtime/action_registry.hpp"
#include "servoloop/realtime/realtime_handoff.hpp"

namespace servoloop::controllers::gripper_action_controller {

// One gripper goal, shared by its sender and the controller.
class GripperGoal {
 public:
  using State = servoloop::realtime::GoalState;
  explicit GripperGoal(const servoloop::control_msgs::GripperCommand& command) : command_(command) {}

  const servoloop::control_msgs::GripperCommand& command() const noexcept { return command_; }
  State state() const noexcept { return state_.load(std::memory_order_acquire); }
  // Meaningful once the goal ended (state() says so).
  const servoloop::control_msgs::GripperCommandResult& result() const noexcept { return result_; }
  void requestCancel() noexcept { cancel_requested_.store(true, std::memory_order_release); }
  bool cancelRequested() const noexcept { return cancel_requested_.load(std::memory_order_acquire); }

  // The controller's side (real-time safe): result first, then the state.
  void setActive() noexcept { state_.store(State::active, std::memory_order_release); }
  // reason: why it ended (a string literal, or null), read by reason().
  void finish(State state, const servoloop::control_msgs::GripperCommandResult& result,
              const char* reason = nullptr) noexcept {
    result_ = result;
    reason_.store(reason, std::memory_order_relaxed);
    state_.store(state, std::memory_order_release);
  }
  // Non-real-time, before the goal is handed over: refused, with why.
  void reject(const servoloop::control_msgs::GripperCommandResult& result, std::string why) {
    rejection_ = std::move(why);
    finish(State::rejected, result);
  }
  // Why it ended ("" when it succeeded, or its result says it: stalled).
  std::string reason() const {
    if (state() == State::rejected) return rejection_;
    const char* reason = reason_.load(std::memory_order_relaxed);
    return reason != nullptr ? reason : "";
  }

 private:
  servoloop::control_msgs::GripperCommand command_;
  servoloop::control_msgs::GripperCommandResult result_;
  std::string rejection_;
  std::atomic<const char*> reason_{nullptr};
  std::atomic<State> state_{State::pending};
  std::atomic<bool> cancel_requested_{false};
};

// The newest feedback of the running goal (the real-time side only try_locks).
struct GripperFeedback {
  std::mutex mutex;
  const GripperGoal* goal = nullptr;
  servoloop::control_msgs::GripperCommandFeedback feedback;
};

template <class Interface>
class GripperActionController : public controller_manager::Controller<Interface> {
 public:
  GripperActionController() = default;
  ~GripperActionController() override;

  // Non-real-time. Throws servoloop::ConfigError naming the parameter.
  bool init(Interface* hw, const controller_manager::ControllerContext& context) override;
  // Real-time.
  void starting(const Time& time) override;
  void stopping(const Time& time) override;
  // Real-time: stopped for a fault; the running goal is aborted with why.
  void setSafeOutput() override;
  ReturnType update(const Time& time, const Duration& period) override;
  // Non-real-time: on an effort interface, the finger joint's PID as "gains/<joint>".
  std::vector<controller_manager::TunablePid> tunablePids() override {
    if (!pid_) return {};
    return {{pid_name_, pid_.get()}};
  }

  // Non-real-time (what the gripper_cmd action calls). Never null; while the
  // controller is not running the goal comes back rejected.
  std::shared_ptr<GripperGoal> sendGoal(const servoloop::control_msgs::GripperCommand& command);

  // Controller thread, or once it stopped (tests and diagnostics).
  double commandedPosition() const noexcept { return command_position_; }
  double commandedEffort() const noexcept { return computed_effort_; }
  const std::shared_ptr<GripperFeedback>& feedbackStore() const noexcept { return feedback_; }

 private:
  struct Item {
    std::shared_ptr<GripperGoal> goal;
  };
  void finishActive(GripperGoal::State state, bool stalled, bool reached, double position) noexcept;
  void holdCurrentPosition() noexcept;
  void stopFollowing(const char* reason) noexcept;

  typename Interface::Handle joint_;
  std::unique_ptr<Pid> pid_;  // effort interface
  std::string pid_name_;      // "gains/<joint>"
  double goal_tolerance_ = 0.01;
  double default_max_effort_ = 0.0;
  double stall_velocity_threshold_ = 0.001;
  double stall_timeout_ = 1.0;
  PeriodicGate feedback_gate_;
  std::string name_;

  servoloop::realtime::RealtimeHandoff<Item> handoff_;
  std::mutex send_mutex_;  // one sender at a time
  std::shared_ptr<GripperFeedback> feedback_ = std::make_shared<GripperFeedback>();
  servoloop::realtime::ActionRegistration action_registration_;
  std::atomic<bool> running_{false};

  // Controller-thread state.
  Item* active_ = nullptr;
  double command_position_ = 0.0;
  double max_effort_ = 0.0;
  double computed_effort_ = 0.0;
  double last_movement_time_ = 0.0;
};

using PositionGripperActionController = GripperActionController<hardware_interface::PositionJointInterface>;
using EffortGripperActionController = GripperActionController<hardware_interface::EffortJointInterface>;

extern template class GripperActionController<hardware_interface::PositionJointInterface>;
extern template class GripperActionController<hardware_interface::EffortJointInterface>;

}  // namespace servoloop::controllers::gripper_action_controller
