#include "servoloop/controllers/joint_trajectory_controller/trajectory_follower.hpp"

#include <algorithm>
#include <cmath>

#include "servoloop/controllers/common/angles.hpp"
#include "servoloop/controllers/common/controller_params.hpp"
#include "servoloop/controllers/joint_trajectory_controller/follow_joint_trajectory_action.hpp"
#include "servoloop/realtime/action_registry.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/realtime/topic_bus.hpp"

namespace servoloop::controllers::joint_trajectory_controller {

namespace {

void resizePoint(servoloop::trajectory_msgs::JointTrajectoryPoint& point, std::size_t joints) {
  point.positions.assign(joints, 0.0);
  point.velocities.assign(joints, 0.0);
  point.accelerations.assign(joints, 0.0);
}

}  // namespace

TrajectoryFollower::~TrajectoryFollower() {
  action_registration_.reset();  // no goal arrives from here on
  command_subscription_ = {};
  dropped_reporter_ = {};
  // The controller is not running any more: no goal is left without a result.
  running_.store(false, std::memory_order_release);
  if (Command* pending = handoff_.take()) {
    abortPending(pending, kUnloadedReason);
    delete pending;
  }
  finishActive(GoalStatus::aborted, TrajectoryErrorCode::invalid_goal, -1, kUnloadedReason);
  delete active_;
  active_ = nullptr;
}

void TrajectoryFollower::abortPending(Command* command, const char* reason) noexcept {
  if (command != nullptr && command->goal && !command->goal->done()) {
    command->goal->finish(GoalStatus::aborted, TrajectoryErrorCode::invalid_goal, -1, reason);
  }
}

void TrajectoryFollower::init(const controller_manager::ControllerContext& context,
                              const std::vector<std::string>& joint_names) {
  controller_name_ = context.name;
  joint_names_ = joint_names;
  const std::size_t n = joint_names.size();
  position_errors_.assign(n, JointPositionError());
  continuous_.assign(n, false);
  if (context.robot_model) {
    for (std::size_t j = 0; j < n; ++j) {
      position_errors_[j] = JointPositionError::fromModel(*context.robot_model, joint_names[j], context.name);
      continuous_[j] = position_errors_[j].kind() == JointPositionError::Kind::continuous;
    }
  } else {
    logger().warn("controller '{}': no robot description was given, so no joint is taken as continuous "
                  "(errors are plain differences)",
                  context.name);
  }
  default_tolerances_ = readTolerances(context, joint_names);
  stop_trajectory_duration_ = optionalNonNegative(context, "stop_trajectory_duration", 0.0);
  state_gate_.setRate(optionalNonNegative(context, "state_publish_rate", 50.0));
  action_monitor_rate_ = optionalNonNegative(context, "action_monitor_rate", 20.0);
  feedback_gate_.setRate(action_monitor_rate_);
  allow_partial_joints_goal_ = optionalBool(context, "allow_partial_joints_goal", false);

  hold_.assign(n, SplineSegment{});
  desired_.assign(n, {});
  error_.assign(n, {});
  actual_.assign(n, {});
  current_.assign(n, {});

  command_topic_ = controllerTopic(context, "command");
  if (context.topics != nullptr) {
    StateMessage prototype;
    prototype.joint_names = joint_names;
    resizePoint(prototype.desired, n);
    resizePoint(prototype.actual, n);
    resizePoint(prototype.error, n);
    state_publisher_ = context.topics->advertise<StateMessage>(controllerTopic(context, "state"), prototype);
    command_subscription_ = context.topics->subscribe<TrajectoryMessage>(
        command_topic_, [this](const TrajectoryMessage& msg) { onTopicMessage(msg); });
    // What the control thread drops is warned about here, on the delivery thread.
    const std::string dropped_topic = controllerTopic(context, "trajectory_dropped");
    servoloop::std_msgs::Float64MultiArray dropped_prototype;
    dropped_prototype.data.assign(3, 0.0);
    dropped_publisher_ =
        context.topics->advertise<servoloop::std_msgs::Float64MultiArray>(dropped_topic, dropped_prototype);
    dropped_reporter_ = context.topics->subscribe<servoloop::std_msgs::Float64MultiArray>(
        dropped_topic, [name = context.name, joints = joint_names](const servoloop::std_msgs::Float64MultiArray& msg) {
          if (msg.data.size() < 3) return;
          if (msg.data[0] == 1.0) {
            logger().warn("controller '{}': trajectory refused: every point is in the past: the trajectory ends at "
                          "{} s and the control time is {} s (stamp 0 starts it on arrival)",
                          name, msg.data[1], msg.data[2]);
          } else if (msg.data[0] == 2.0) {
            const auto j = static_cast<std::size_t>(msg.data[1]);
            logger().warn("controller '{}': the desired state of joint '{}' became non-finite at t = {} s (the "
                          "trajectory's values are too large for its spline arithmetic): the trajectory (and its "
                          "goal) was aborted and the joints hold",
                          name, j < joints.size() ? joints[j] : std::string("?"), msg.data[2]);
          }
        });
  }
  {
    auto& feedback = goal_feedback_->feedback;
    feedback.joint_names = joint_names;
    resizePoint(feedback.desired, n);
    resizePoint(feedback.actual, n);
    resizePoint(feedback.error, n);
  }
  if (context.actions != nullptr) {
    action_registration_ =
        context.actions->add(controllerTopic(context, "follow_joint_trajectory"),
                             servoloop::control_msgs::FollowJointTrajectoryGoal::kActionType,
                             std::make_shared<FollowJointTrajectoryAction>(*this));
  }
}

// --- non-real-time ------------------------------------------------------------------

std::unique_ptr<TrajectoryFollower::Command> TrajectoryFollower::makeCommand(const TrajectoryMessage& msg,
                                                                             TrajectoryErrorCode& code) {
  const std::size_t n = joint_names_.size();
  auto command = std::make_unique<Command>();
  if (msg.points.empty()) {
    command->stop = true;
    return command;
  }
  // Where each of the message's joints is in the controller's order.
  code = TrajectoryErrorCode::invalid_joints;
  std::vector<std::size_t> index_of(msg.joint_names.size());
  std::vector<bool> named(n, false);
  for (std::size_t k = 0; k < msg.joint_names.size(); ++k) {
    const auto it = std::find(joint_names_.begin(), joint_names_.end(), msg.joint_names[k]);
    if (it == joint_names_.end()) {
      throw Error("joint_names[" + std::to_string(k) + "] '" + msg.joint_names[k] +
                  "' is not a joint of the controller (" + joinNames(joint_names_) + ")");
    }
    const auto j = static_cast<std::size_t>(it - joint_names_.begin());
    if (named[j]) throw Error("joint_names lists '" + msg.joint_names[k] + "' twice");
    named[j] = true;
    index_of[k] = j;
  }
  std::vector<bool> held(n, false);
  std::vector<std::string> missing;
  for (std::size_t j = 0; j < n; ++j) {
    if (!named[j]) {
      held[j] = true;
      missing.push_back(joint_names_[j]);
    }
  }
  if (!missing.empty() && !allow_partial_joints_goal_) {
    throw Error("joint_names leaves out " + joinNames(missing) +
                "; name every joint of the controller, or set allow_partial_joints_goal: true");
  }

  code = TrajectoryErrorCode::invalid_goal;
  std::vector<TrajectoryPoint> points(msg.points.size());
  for (std::size_t i = 0; i < msg.points.size(); ++i) {
    const auto& given = msg.points[i];
    const std::string where = "points[" + std::to_string(i) + "]";
    const auto reorder = [&](const std::vector<double>& values, const char* field, std::vector<double>& out) {
      if (values.empty()) return;
      if (values.size() != msg.joint_names.size()) {
        throw Error(where + "." + field + " has " + std::to_string(values.size()) + " values for " +
                    std::to_string(msg.joint_names.size()) + " joint_names; give one per joint" +
                    (std::string(field) == "positions" ? "" : " or none"));
      }
      out.assign(n, 0.0);
      for (std::size_t k = 0; k < values.size(); ++k) out[index_of[k]] = values[k];
    };
    if (given.positions.empty()) throw Error(where + ".positions is empty; give one position per joint");
    const auto finite = [&](const std::vector<double>& values, const char* field) {
      for (std::size_t k = 0; k < values.size() && k < msg.joint_names.size(); ++k) {
        if (!std::isfinite(values[k])) {
          throw Error(where + "." + field + "[" + std::to_string(k) + "] (joint '" + msg.joint_names[k] +
                      "', point index " + std::to_string(i) + ") is " + std::to_string(values[k]) +
                      ", not a finite number");
        }
      }
    };
    finite(given.positions, "positions");
    finite(given.velocities, "velocities");
    finite(given.accelerations, "accelerations");
    reorder(given.positions, "positions", points[i].positions);
    reorder(given.velocities, "velocities", points[i].velocities);
    reorder(given.accelerations, "accelerations", points[i].accelerations);
    points[i].time_from_start = given.time_from_start;
  }
  // Values finite but so large that interpolating them overflows (1e308):
  // each segment between points, and the first point reached from rest at 0.
  for (std::size_t j = 0; j < n; ++j) {
    if (held[j]) continue;
    JointSample previous{};
    double previous_time = std::min(0.0, points.front().time_from_start - 1.0);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const TrajectoryPoint& point = points[i];
      const JointSample state{point.positions[j], point.velocities.empty() ? 0.0 : point.velocities[j],
                              point.accelerations.empty() ? 0.0 : point.accelerations[j]};
      const SplineKind kind = !point.accelerations.empty()  ? SplineKind::quintic
                              : !point.velocities.empty()   ? SplineKind::cubic
                                                            : SplineKind::linear;
      if (!SplineSegment(previous_time, previous, point.time_from_start, state, kind).finite()) {
        throw Error("points[" + std::to_string(i) + "] (point index " + std::to_string(i) + ", joint '" +
                    joint_names_[j] + "'): interpolating to it overflows (position " +
                    std::to_string(state.position) + ", velocity " + std::to_string(state.velocity) +
                    ", acceleration " + std::to_string(state.acceleration) +
                    "); give values the joint can reach");
      }
      previous = state;
      previous_time = point.time_from_start;
    }
  }
  command->trajectory = JointTrajectory::fromPoints(msg.stamp, points, n, continuous_, held);

  const double now = last_time_.load(std::memory_order_acquire);
  // stamp 0 (or less) starts the trajectory on arrival: it lies in the past
  // when no point has a time_from_start after 0.
  const double end = msg.stamp > 0.0 ? command->trajectory.endTime() : now + points.back().time_from_start;
  if (!(end > now)) {
    code = TrajectoryErrorCode::old_header_timestamp;
    throw Error("every point is in the past: the trajectory ends at " + std::to_string(end) +
                " s and the control time is " + std::to_string(now) + " s (stamp 0 starts it on arrival)");
  }
  code = TrajectoryErrorCode::successful;
  return command;
}

void TrajectoryFollower::push(std::unique_ptr<Command> command) {
  const std::lock_guard lock(push_mutex_);  // the topic's thread and a goal's sender
  std::unique_ptr<Command> replaced = handoff_.push(std::move(command));
  if (replaced && replaced->goal) replaced->goal->finish(GoalStatus::preempted, TrajectoryErrorCode::successful);
  // The controller stopped after the caller checked it ran: stop() took
  // what was there before this push, so this one would wait for the next
  // start. Taken back here instead (only pushers, under this lock, and the
  // control thread take; each item goes to exactly one of them), its goal
  // ends now.
  if (!running_.load(std::memory_order_acquire)) {
    std::unique_ptr<Command> stale(handoff_.take());
    if (stale) abortPending(stale.get(), kNotRunningReason);
  }
}

void TrajectoryFollower::onTopicMessage(const TrajectoryMessage& msg) {
  if (!running_.load(std::memory_order_acquire)) {
    refused_.fetch_add(1, std::memory_order_relaxed);
    // Once per stop, so a publisher that keeps going does not flood the log.
    if (!stopped_warning_logged_.exchange(true)) {
      logger().warn("controller '{}': trajectory on {} ignored: the controller is not running; start it first "
                    "(further ones are only counted until it starts)",
                    controller_name_, command_topic_);
    }
    return;
  }
  TrajectoryErrorCode code = TrajectoryErrorCode::successful;
  try {
    push(makeCommand(msg, code));
  } catch (const Error& e) {
    refused_.fetch_add(1, std::memory_order_relaxed);
    logger().warn("controller '{}': trajectory on {} ignored: {}", controller_name_, command_topic_, e.what());
  }
}

std::shared_ptr<TrajectoryGoal> TrajectoryFollower::submitGoal(const TrajectoryMessage& msg,
                                                               TrajectoryTolerances tolerances) {
  auto goal = std::make_shared<TrajectoryGoal>(std::move(tolerances));
  if (!running_.load(std::memory_order_acquire)) {
    goal->reject(TrajectoryErrorCode::invalid_goal,
                 "controller '" + controller_name_ + "' is not running; start it first");
    return goal;
  }
  if (goal->tolerances().path.size() != joint_names_.size() || goal->tolerances().goal.size() != joint_names_.size()) {
    goal->reject(TrajectoryErrorCode::invalid_goal, "the tolerances do not match the controller's joints");
    return goal;
  }
  TrajectoryErrorCode code = TrajectoryErrorCode::successful;
  try {
    std::unique_ptr<Command> command = makeCommand(msg, code);
    command->goal = goal;
    push(std::move(command));
  } catch (const Error& e) {
    goal->reject(code, e.what());
    if (code == TrajectoryErrorCode::old_header_timestamp) {
      logger().warn("controller '{}': trajectory goal refused: {}", controller_name_, e.what());
    }
  }
  return goal;
}

// --- real-time -------------------------------------------------------------------------

void TrajectoryFollower::start(const Time& time, const std::vector<double>& actual_positions,
                               const std::vector<double>& actual_velocities) noexcept {
  for (std::size_t j = 0; j < desired_.size(); ++j) {
    desired_[j] = {actual_positions[j], actual_velocities[j], 0.0};
    error_[j] = {};
  }
  // A trajectory sent while stopped was refused, but one may have crossed
  // over just before the stop: it is not followed.
  if (Command* stale = handoff_.take()) {
    if (stale->goal) stale->goal->finish(GoalStatus::aborted, TrajectoryErrorCode::invalid_goal, -1, kNotRunningReason);
    handoff_.retire(stale);
  }
  hold(time.seconds);
  last_time_.store(time.seconds, std::memory_order_release);
  state_gate_.reset();
  stopped_warning_logged_.store(false, std::memory_order_relaxed);
  running_.store(true, std::memory_order_release);
}

void TrajectoryFollower::stop() noexcept {
  // As ros_controllers' stopping(): the running goal is preempted.
  stopFollowing(GoalStatus::preempted, TrajectoryErrorCode::successful, kStoppedReason);
}

void TrajectoryFollower::stopForFault() noexcept {
  stopFollowing(GoalStatus::aborted, TrajectoryErrorCode::invalid_goal, kFaultReason);
}

void TrajectoryFollower::stopFollowing(GoalStatus status, TrajectoryErrorCode code, const char* reason) noexcept {
  running_.store(false, std::memory_order_release);
  finishActive(status, code, -1, reason);
  handoff_.retire(active_);
  active_ = nullptr;
  // A goal on its way is not followed either (a push after this sees
  // running_ false and ends its own).
  if (Command* pending = handoff_.take()) {
    abortPending(pending, reason);
    handoff_.retire(pending);
  }
}

void TrajectoryFollower::finishActive(GoalStatus status, TrajectoryErrorCode code, int joint,
                                      const char* reason) noexcept {
  if (active_ != nullptr && active_->goal && !active_->goal->done()) {
    active_->goal->finish(status, code, joint, reason);
  }
}

bool TrajectoryFollower::desiredFinite(std::size_t& joint) const noexcept {
  for (std::size_t j = 0; j < desired_.size(); ++j) {
    if (!std::isfinite(desired_[j].position) || !std::isfinite(desired_[j].velocity) ||
        !std::isfinite(desired_[j].acceleration)) {
      joint = j;
      return false;
    }
  }
  return true;
}

void TrajectoryFollower::reportDropped(double kind, double a, double b) noexcept {
  if (!dropped_publisher_.valid() || !dropped_publisher_.trylock()) return;
  auto& data = dropped_publisher_.msg().data;
  data[0] = kind;
  data[1] = a;
  data[2] = b;
  dropped_publisher_.unlockAndPublish();
}

void TrajectoryFollower::hold(double now) noexcept {
  // Come to rest from the desired state in stop_trajectory_duration: the
  // quintic from (p, v) to (p, -v) over twice that time is at rest half way;
  // the hold runs from (p, v) to that state.
  const double stop = stop_trajectory_duration_;
  for (std::size_t j = 0; j < hold_.size(); ++j) {
    const JointSample from{desired_[j].position, desired_[j].velocity, 0.0};
    if (!(stop > 0.0)) {
      const JointSample rest{from.position, 0.0, 0.0};
      hold_[j] = SplineSegment(now, rest, now, rest, SplineKind::linear);
      continue;
    }
    const SplineSegment there_and_back(now, from, now + 2.0 * stop, {from.position, -from.velocity, 0.0},
                                       SplineKind::quintic);
    hold_[j] = SplineSegment(now, from, now + stop, there_and_back.sample(now + stop), SplineKind::quintic);
  }
  handoff_.retire(active_);
  active_ = nullptr;
}

void TrajectoryFollower::sampleDesired(double now) noexcept {
  if (active_ != nullptr) {
    active_->trajectory.sample(now, desired_);
  } else {
    for (std::size_t j = 0; j < hold_.size(); ++j) desired_[j] = hold_[j].sample(now);
  }
}

void TrajectoryFollower::applyCommand(Command* command, double now) noexcept {
  // desired_ holds the state wanted now; the new trajectory starts from it.
  if (command->stop) {
    finishActive(GoalStatus::preempted, TrajectoryErrorCode::successful);
    hold(now);
    // A goal with no points asks for a stop, which this is.
    if (command->goal) command->goal->finish(GoalStatus::succeeded, TrajectoryErrorCode::successful);
    handoff_.retire(command);
    return;
  }
  if (!command->trajectory.activate(now, desired_)) {
    // Every point went by between its check and now: keep what runs.
    if (command->goal) command->goal->finish(GoalStatus::aborted, TrajectoryErrorCode::old_header_timestamp);
    refused_.fetch_add(1, std::memory_order_relaxed);
    in_the_past_.fetch_add(1, std::memory_order_relaxed);
    reportDropped(1.0, command->trajectory.startTime() > 0.0 ? command->trajectory.endTime() : now, now);
    handoff_.retire(command);
    return;
  }
  finishActive(GoalStatus::preempted, TrajectoryErrorCode::successful);
  handoff_.retire(active_);
  active_ = command;
  if (active_->goal) {
    active_->goal->setActive();
    feedback_gate_.reset();
  }
  taken_.fetch_add(1, std::memory_order_relaxed);
}

void TrajectoryFollower::update(const Time& time, const Duration& period, const std::vector<double>& actual_positions,
                                const std::vector<double>& actual_velocities) noexcept {
  const double now = time.seconds;
  last_time_.store(now, std::memory_order_release);
  sampleDesired(now);
  if (Command* command = handoff_.take()) [[unlikely]] {
    applyCommand(command, now);
    sampleDesired(now);
  }
  if (active_ != nullptr && active_->goal && active_->goal->cancelRequested()) [[unlikely]] {
    finishActive(GoalStatus::canceled, TrajectoryErrorCode::successful);
    hold(now);
    sampleDesired(now);
  }
  if (std::size_t bad = 0; !desiredFinite(bad)) [[unlikely]] {
    // The trajectory's arithmetic overflowed: its goal ends, the joints hold
    // where they are rather than being handed a NaN.
    finishActive(GoalStatus::aborted, TrajectoryErrorCode::invalid_goal, static_cast<int>(bad), kNonFiniteReason);
    for (std::size_t j = 0; j < desired_.size(); ++j) {
      const bool finite_position = std::isfinite(actual_positions[j]);
      desired_[j] = {finite_position ? actual_positions[j] : 0.0,
                     finite_position && std::isfinite(actual_velocities[j]) ? actual_velocities[j] : 0.0, 0.0};
    }
    hold(now);
    sampleDesired(now);
    non_finite_.fetch_add(1, std::memory_order_relaxed);
    reportDropped(2.0, static_cast<double>(bad), now);
  }

  for (std::size_t j = 0; j < desired_.size(); ++j) {
    actual_[j] = {actual_positions[j], actual_velocities[j], 0.0};
    const double position_error = continuous_[j]
                                      ? shortestAngularDistance(actual_positions[j], desired_[j].position)
                                      : desired_[j].position - actual_positions[j];
    // Acceleration is not measured: its error is taken as 0.
    error_[j] = {position_error, desired_[j].velocity - actual_velocities[j], 0.0};
  }
  if (active_ != nullptr && active_->goal && !active_->goal->done()) {
    if (feedback_gate_.due(time, period)) writeFeedback(now);
    checkTolerances(now);  // may end the goal and hold (active_ then null)
  }
}

void TrajectoryFollower::writeFeedback(double now) noexcept {
  GoalFeedback& store = *goal_feedback_;
  if (!store.mutex.try_lock()) return;  // the sender is reading: next time
  store.goal = active_->goal.get();
  auto& feedback = store.feedback;
  feedback.stamp = now;
  const double since_start = now - active_->trajectory.startTime();
  for (std::size_t j = 0; j < desired_.size(); ++j) {
    feedback.desired.positions[j] = desired_[j].position;
    feedback.desired.velocities[j] = desired_[j].velocity;
    feedback.desired.accelerations[j] = desired_[j].acceleration;
    feedback.actual.positions[j] = actual_[j].position;
    feedback.actual.velocities[j] = actual_[j].velocity;
    feedback.error.positions[j] = error_[j].position;
    feedback.error.velocities[j] = error_[j].velocity;
  }
  feedback.desired.time_from_start = since_start;
  feedback.actual.time_from_start = since_start;
  feedback.error.time_from_start = since_start;
  store.mutex.unlock();
}

void TrajectoryFollower::checkTolerances(double now) noexcept {
  const TrajectoryTolerances& tolerances = active_->goal->tolerances();
  const double end = active_->trajectory.endTime();
  if (now < end) {
    for (std::size_t j = 0; j < error_.size(); ++j) {
      if (!withinTolerance(tolerances.path[j], error_[j].position, error_[j].velocity, error_[j].acceleration)) {
        finishActive(GoalStatus::aborted, TrajectoryErrorCode::path_tolerance_violated, static_cast<int>(j));
        hold(now);
        return;
      }
    }
    return;
  }
  int outside = -1;
  for (std::size_t j = 0; j < error_.size() && outside < 0; ++j) {
    if (!withinTolerance(tolerances.goal[j], error_[j].position, error_[j].velocity, error_[j].acceleration)) {
      outside = static_cast<int>(j);
    }
  }
  if (outside < 0) {
    finishActive(GoalStatus::succeeded, TrajectoryErrorCode::successful);
  } else if (!(now < end + tolerances.goal_time)) {
    finishActive(GoalStatus::aborted, TrajectoryErrorCode::goal_tolerance_violated, outside);
  }
}

void TrajectoryFollower::publishStateIfDue(const Time& time, const Duration& period) noexcept {
  if (!state_gate_.due(time, period)) return;
  if (!state_publisher_.valid() || !state_publisher_.trylock()) return;
  StateMessage& msg = state_publisher_.msg();
  msg.stamp = time.seconds;
  const double since_start = active_ != nullptr ? time.seconds - active_->trajectory.startTime() : 0.0;
  for (std::size_t j = 0; j < desired_.size(); ++j) {
    msg.desired.positions[j] = desired_[j].position;
    msg.desired.velocities[j] = desired_[j].velocity;
    msg.desired.accelerations[j] = desired_[j].acceleration;
    msg.actual.positions[j] = actual_[j].position;
    msg.actual.velocities[j] = actual_[j].velocity;
    msg.actual.accelerations[j] = 0.0;
    msg.error.positions[j] = error_[j].position;
    msg.error.velocities[j] = error_[j].velocity;
    msg.error.accelerations[j] = error_[j].acceleration;
  }
  msg.desired.time_from_start = since_start;
  msg.actual.time_from_start = since_start;
  msg.error.time_from_start = since_start;
  state_publisher_.unlockAndPublish();
}

}  // namespace servoloop::controllers::joint_trajectory_controller
