#include "servoloop/controllers/gripper_action_controller/gripper_action_controller.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "servoloop/controllers/common/controller_params.hpp"
#include "servoloop/controllers/common/joint_handles.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/plugin/plugin_register.hpp"

namespace servoloop::controllers::gripper_action_controller {

namespace hi = hardware_interface;
namespace cm = servoloop::control_msgs;
using GoalState = servoloop::realtime::GoalState;

namespace {

template <class Interface>
constexpr bool kEffort = std::is_same_v<Interface, hi::EffortJointInterface>;

constexpr const char* kStoppedReason =
    "the controller was stopped while the goal ran (a controller switch, or the controller deactivated)";
constexpr const char* kFaultReason =
    "the controller was stopped for a fault (an exception, a non-finite command or a hardware failure: see the "
    "node's log)";
constexpr const char* kUnloadedReason = "the controller was unloaded while the goal ran";
constexpr const char* kNotRunningReason = "the controller stopped before the goal was taken over";

// A goal as its sender sees it; holds what it reads, so it may outlive the controller.
class GripperActionGoal : public servoloop::realtime::ActionGoal {
 public:
  GripperActionGoal(std::shared_ptr<GripperGoal> goal, std::shared_ptr<GripperFeedback> feedback)
      : goal_(std::move(goal)), feedback_(std::move(feedback)) {}
  GoalState state() const override { return goal_->state(); }
  void cancel() override { goal_->requestCancel(); }
  bool feedback(void* out) const override {
    std::lock_guard lock(feedback_->mutex);
    if (feedback_->goal != goal_.get()) return false;
    *static_cast<cm::GripperCommandFeedback*>(out) = feedback_->feedback;
    return true;
  }
  void result(void* out) const override { *static_cast<cm::GripperCommandResult*>(out) = goal_->result(); }
  std::string statusText() const override { return goal_->reason(); }

 private:
  std::shared_ptr<GripperGoal> goal_;
  std::shared_ptr<GripperFeedback> feedback_;
};

template <class Controller>
class GripperCommandAction : public servoloop::realtime::ActionServer {
 public:
  explicit GripperCommandAction(Controller& controller) : controller_(controller) {}
  std::shared_ptr<servoloop::realtime::ActionGoal> sendGoal(const void* goal) override {
    const auto& message = *static_cast<const cm::GripperCommandGoal*>(goal);
    return std::make_shared<GripperActionGoal>(controller_.sendGoal(message.command), controller_.feedbackStore());
  }

 private:
  Controller& controller_;  // outlives the registration, which it owns
};

}  // namespace

template <class Interface>
GripperActionController<Interface>::~GripperActionController() {
  action_registration_.reset();  // no goal arrives from here on
  running_.store(false, std::memory_order_release);
  // No goal is left without a result.
  if (Item* pending = handoff_.take()) {
    if (!servoloop::realtime::goalDone(pending->goal->state())) {
      pending->goal->finish(GoalState::aborted, {}, kUnloadedReason);
    }
    delete pending;
  }
  if (active_ != nullptr) {
    if (!servoloop::realtime::goalDone(active_->goal->state())) {
      active_->goal->finish(GoalState::aborted, active_->goal->result(), kUnloadedReason);
    }
    delete active_;
  }
}

template <class Interface>
bool GripperActionController<Interface>::init(Interface* hw, const controller_manager::ControllerContext& context) {
  name_ = context.name;
  const std::string joint_name = requireString(context, "joint", "joint: finger_joint");
  if constexpr (kEffort<Interface>) {
    const std::string key = "gains/" + joint_name;
    if (context.params.child(key).empty()) {
      throw ConfigError("controller '" + context.name + "': parameter '" + parameterPath(context, key) +
                        "' is missing; an effort gripper controller needs PID gains for its joint, e.g. 'gains: {" +
                        joint_name + ": {p: 100, d: 1}}'");
    }
    pid_ = std::make_unique<Pid>();
    pid_name_ = key;
    pid_->initFromParams(context.params.child(key), parameterPath(context, key));
  }
  goal_tolerance_ = optionalNonNegative(context, "goal_tolerance", 0.01);
  default_max_effort_ = optionalNonNegative(context, "max_effort", 0.0);
  stall_velocity_threshold_ = optionalNonNegative(context, "stall_velocity_threshold", 0.001);
  stall_timeout_ = optionalNonNegative(context, "stall_timeout", 1.0);
  feedback_gate_.setRate(optionalNonNegative(context, "action_monitor_rate", 20.0));
  joint_ = getJointHandle(*hw, joint_name, context, "joint");
  if (context.actions != nullptr) {
    action_registration_ =
        context.actions->add(controllerTopic(context, "gripper_cmd"), cm::GripperCommandGoal::kActionType,
                             std::make_shared<GripperCommandAction<GripperActionController>>(*this));
  }
  return true;
}

template <class Interface>
std::shared_ptr<GripperGoal> GripperActionController<Interface>::sendGoal(const cm::GripperCommand& command) {
  auto goal = std::make_shared<GripperGoal>(command);
  if (!running_.load(std::memory_order_acquire)) {
    cm::GripperCommandResult result;
    result.position = joint_.getPosition();
    std::string why = "controller '" + name_ + "' is not running; start it with servoloop control start " + name_;
    logger().warn("gripper goal rejected: {}", why);
    goal->reject(result, std::move(why));
    return goal;
  }
  std::lock_guard lock(send_mutex_);
  auto item = std::make_unique<Item>();
  item->goal = goal;
  if (std::unique_ptr<Item> replaced = handoff_.push(std::move(item))) {
    replaced->goal->finish(GoalState::preempted, {});
  }
  // Stopped since the check above: stopping() took what was there before
  // this push; this goal is taken back (only senders, under the lock, and
  // the control thread take) and ends now instead of at the next start.
  if (!running_.load(std::memory_order_acquire)) {
    std::unique_ptr<Item> stale(handoff_.take());
    if (stale && !servoloop::realtime::goalDone(stale->goal->state())) {
      stale->goal->finish(GoalState::aborted, {}, kNotRunningReason);
    }
  }
  return goal;
}

template <class Interface>
void GripperActionController<Interface>::starting(const Time& time) {
  command_position_ = joint_.getPosition();
  max_effort_ = default_max_effort_;
  computed_effort_ = 0.0;
  last_movement_time_ = time.seconds;
  if (pid_) pid_->reset();
  // A goal that crossed over before a stop is not followed.
  if (Item* stale = handoff_.take()) {
    stale->goal->finish(GoalState::aborted, {}, kNotRunningReason);
    handoff_.retire(stale);
  }
  feedback_gate_.reset();
  running_.store(true, std::memory_order_release);
}

template <class Interface>
void GripperActionController<Interface>::finishActive(GoalState state, bool stalled, bool reached,
                                                      double position) noexcept {
  if (active_ == nullptr) return;
  if (!servoloop::realtime::goalDone(active_->goal->state())) {
    active_->goal->finish(state, cm::GripperCommandResult{position, computed_effort_, stalled, reached});
  }
  handoff_.retire(active_);
  active_ = nullptr;
}

template <class Interface>
void GripperActionController<Interface>::stopFollowing(const char* reason) noexcept {
  running_.store(false, std::memory_order_release);
  const double position = joint_.getPosition();
  if (active_ != nullptr) {
    if (!servoloop::realtime::goalDone(active_->goal->state())) {
      active_->goal->finish(GoalState::aborted, cm::GripperCommandResult{position, computed_effort_, false, false},
                            reason);
    }
    handoff_.retire(active_);
    active_ = nullptr;
  }
  if (Item* pending = handoff_.take()) {
    if (!servoloop::realtime::goalDone(pending->goal->state())) {
      pending->goal->finish(GoalState::aborted, cm::GripperCommandResult{position, 0.0, false, false}, reason);
    }
    handoff_.retire(pending);
  }
}

template <class Interface>
void GripperActionController<Interface>::setSafeOutput() {
  stopFollowing(kFaultReason);
  computed_effort_ = 0.0;
}

template <class Interface>
void GripperActionController<Interface>::stopping(const Time& /*time*/) {
  stopFollowing(kStoppedReason);
  if constexpr (kEffort<Interface>) {
    computed_effort_ = 0.0;
    joint_.setCommand(0.0);
  }
}

template <class Interface>
ReturnType GripperActionController<Interface>::update(const Time& time, const Duration& period) {
  const double position = joint_.getPosition();
  const double velocity = joint_.getVelocity();
  if (Item* item = handoff_.take()) [[unlikely]] {
    finishActive(GoalState::preempted, false, false, position);
    active_ = item;
    active_->goal->setActive();
    command_position_ = item->goal->command().position;
    max_effort_ = item->goal->command().max_effort;
    last_movement_time_ = time.seconds;
    feedback_gate_.reset();
  }
  if (active_ != nullptr && active_->goal->cancelRequested()) [[unlikely]] {
    command_position_ = position;  // hold where it is
    finishActive(GoalState::canceled, false, false, position);
  }

  const double error = command_position_ - position;
  if constexpr (kEffort<Interface>) {
    const double limit = std::abs(max_effort_);
    computed_effort_ = std::clamp(pid_->computeCommand(error, -velocity, period.seconds), -limit, limit);
    joint_.setCommand(computed_effort_);
  } else {
    computed_effort_ = max_effort_;
    joint_.setCommand(command_position_);
  }

  if (active_ != nullptr) {
    if (std::abs(error) < goal_tolerance_) {
      finishActive(GoalState::succeeded, false, true, position);
    } else if (std::abs(velocity) > stall_velocity_threshold_) {
      last_movement_time_ = time.seconds;
    } else if (time.seconds - last_movement_time_ > stall_timeout_) {
      finishActive(GoalState::aborted, true, false, position);
    }
  }
  if (active_ != nullptr && feedback_gate_.due(time, period) && feedback_->mutex.try_lock()) {
    feedback_->goal = active_->goal.get();
    feedback_->feedback = cm::GripperCommandFeedback{position, computed_effort_, false, false};
    feedback_->mutex.unlock();
  }
  return ReturnType::ok;
}

template class GripperActionController<hi::PositionJointInterface>;
template class GripperActionController<hi::EffortJointInterface>;

}  // namespace servoloop::controllers::gripper_action_controller

SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::gripper_action_controller::PositionGripperActionController,
                          servoloop::controller_manager::ControllerBase,
                          "position_controllers/GripperActionController")
SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::gripper_action_controller::EffortGripperActionController,
                          servoloop::controller_manager::ControllerBase,
                          "effort_controllers/GripperActionController")
