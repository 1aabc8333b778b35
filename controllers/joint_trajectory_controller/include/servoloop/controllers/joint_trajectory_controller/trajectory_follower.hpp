#pragma once
// What every joint trajectory controller does whatever its hardware
// interface: takes trajectories (the `command` topic, and goals), follows
// them in time, checks a goal's tolerances, holds when there is nothing to
// follow, and publishes the `state` topic. The controller turns the desired
// state and the error into joint commands.
//
// Threads: connect() and submitGoal() run off the real-time thread (the
// topic's messages arrive on the bus's delivery thread); start(), stop() and
// update() run on it and neither allocate nor block. Trajectories cross over
// through a RealtimeHandoff.
//
// Behaviour (ros_controllers' joint_trajectory_controller):
//   - start(): hold the current position (with stop_trajectory_duration > 0,
//     come to rest from the current velocity within that time);
//   - a trajectory with no points stops: hold, as a cancel does;
//   - a new trajectory (or goal) replaces the current one from its start
//     time; the goal it replaces is preempted;
//   - a goal's path tolerance is checked while its trajectory runs, its goal
//     tolerance from the last point's time on (for goal_time more); a
//     violation aborts the goal and the joints stop within
//     stop_trajectory_duration;
//   - trajectories from the topic are followed without tolerance checks;
//   - while the controller is stopped, trajectories are refused; stopping
//     it (a switch, a fault, unloading it) aborts its goal, and one still on
//     its way, with the reason in the result's error_string;
//   - a desired state that is not finite (values so large that the spline's
//     arithmetic overflows) aborts the goal and holds, instead of handing
//     the joints a NaN;
//   - a trajectory that lies wholly in the past is refused with a warning
//     naming both times; one whose points all went by between its check and
//     the control thread taking it is dropped with the same warning, logged
//     on the bus's delivery thread (<controller>/trajectory_dropped).
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "servoloop/controller_manager/controller_context.hpp"
#include "servoloop/controllers/common/joint_position_error.hpp"
#include "servoloop/controllers/common/joint_trajectory.hpp"
#include "servoloop/controllers/common/periodic_gate.hpp"
#include "servoloop/controllers/joint_trajectory_controller/trajectory_goal.hpp"
#include "servoloop/controllers/joint_trajectory_controller/trajectory_tolerances.hpp"
#include "servoloop/core/time.hpp"
#include "servoloop/realtime/action_messages.hpp"
#include "servoloop/realtime/action_registry.hpp"
#include "servoloop/realtime/messages.hpp"
#include "servoloop/realtime/realtime_handoff.hpp"
#include "servoloop/realtime/realtime_publisher.hpp"
#include "servoloop/realtime/topic_subscription.hpp"

namespace servoloop::controllers::joint_trajectory_controller {

class TrajectoryFollower {
 public:
  using StateMessage = servoloop::control_msgs::JointTrajectoryControllerState;
  using TrajectoryMessage = servoloop::trajectory_msgs::JointTrajectory;

  TrajectoryFollower() = default;
  TrajectoryFollower(const TrajectoryFollower&) = delete;
  TrajectoryFollower& operator=(const TrajectoryFollower&) = delete;
  ~TrajectoryFollower();

  // Non-real-time. Reads joints' types (continuous joints wrap) from the
  // robot model, the parameters (constraints, stop_trajectory_duration,
  // state_publish_rate, action_monitor_rate, allow_partial_joints_goal),
  // subscribes to <controller>/command, advertises <controller>/state and
  // serves the action <controller>/follow_joint_trajectory
  // (control_msgs/FollowJointTrajectory).
  // Throws servoloop::ConfigError naming the parameter.
  void init(const controller_manager::ControllerContext& context, const std::vector<std::string>& joint_names);

  // Non-real-time: a goal for msg with the given tolerances (the defaults:
  // defaultTolerances()). The goal comes back rejected (with the error code
  // and why) when msg names joints the controller lacks, leaves some out
  // without allow_partial_joints_goal, holds malformed points, ends before
  // the current control time, or the controller is not running. A goal
  // replaces the one before it.
  std::shared_ptr<TrajectoryGoal> submitGoal(const TrajectoryMessage& msg, TrajectoryTolerances tolerances);

  // Real-time. actual_positions/velocities: one per joint.
  void start(const Time& time, const std::vector<double>& actual_positions,
             const std::vector<double>& actual_velocities) noexcept;
  // Real-time: stops following. stop() (a switch) preempts the running goal,
  // as ros_controllers' stopping() does; stopForFault() aborts it. Either
  // gives the reason below as its error_string and aborts a goal not taken yet.
  void stop() noexcept;
  void stopForFault() noexcept;

  // Why goals end when their controller stops (error_string of the result).
  static constexpr const char* kStoppedReason =
      "the controller was stopped while the goal ran (a controller switch, or the controller deactivated); "
      "start it again and resend the goal";
  static constexpr const char* kFaultReason =
      "the controller was stopped for a fault (an exception, a non-finite command or a hardware failure: see "
      "the node's log); start it again and resend the goal";
  static constexpr const char* kUnloadedReason = "the controller was unloaded while the goal ran";
  static constexpr const char* kNonFiniteReason =
      "the desired state became non-finite (the trajectory's values are too large for its spline "
      "arithmetic); the joints hold";
  static constexpr const char* kNotRunningReason = "the controller stopped before the goal was taken over";
  // Real-time: takes a new trajectory if one came, samples the desired state
  // at time, computes the error against the actual state and checks the
  // goal's tolerances. Read the results with desired() and error().
  void update(const Time& time, const Duration& period, const std::vector<double>& actual_positions,
              const std::vector<double>& actual_velocities) noexcept;
  // Real-time: publishes the state topic when it is due (state_publish_rate).
  void publishStateIfDue(const Time& time, const Duration& period) noexcept;

  const std::vector<JointSample>& desired() const noexcept { return desired_; }
  const std::vector<JointSample>& error() const noexcept { return error_; }  // desired - actual
  const std::vector<std::string>& jointNames() const noexcept { return joint_names_; }
  const TrajectoryTolerances& defaultTolerances() const noexcept { return default_tolerances_; }
  double stopTrajectoryDuration() const noexcept { return stop_trajectory_duration_; }
  double actionMonitorRate() const noexcept { return action_monitor_rate_; }
  bool allowPartialJointsGoal() const noexcept { return allow_partial_joints_goal_; }
  // Controller thread: whether a trajectory (not a hold) is being followed.
  bool following() const noexcept { return active_ != nullptr; }
  // The newest feedback of the running goal, written by the real-time thread
  // at action_monitor_rate and read by the goal's sender.
  struct GoalFeedback {
    std::mutex mutex;  // the real-time thread only try_locks it
    const TrajectoryGoal* goal = nullptr;
    servoloop::control_msgs::FollowJointTrajectoryFeedback feedback;
  };
  const std::shared_ptr<GoalFeedback>& goalFeedback() const noexcept { return goal_feedback_; }

  // Any thread: trajectories taken over, and those refused on the topic.
  std::uint64_t trajectoriesTaken() const noexcept { return taken_.load(std::memory_order_relaxed); }
  std::uint64_t trajectoriesRefused() const noexcept { return refused_.load(std::memory_order_relaxed); }
  // Any thread: trajectories (topic or goal) dropped by the control thread
  // because every point had gone by when it took them, and trajectories
  // stopped because their desired state was not finite. Each is also
  // warned about in the log.
  std::uint64_t trajectoriesInThePast() const noexcept { return in_the_past_.load(std::memory_order_relaxed); }
  std::uint64_t nonFiniteDesiredStates() const noexcept { return non_finite_.load(std::memory_order_relaxed); }

 private:
  // A trajectory on its way to or in use by the real-time thread.
  struct Command {
    JointTrajectory trajectory;
    std::shared_ptr<TrajectoryGoal> goal;  // null for the topic's
    bool stop = false;                     // no points: hold
  };

  // Non-real-time: msg in the controller's joint order, or an Error saying
  // why not (code: the result code a goal gets).
  std::unique_ptr<Command> makeCommand(const TrajectoryMessage& msg, TrajectoryErrorCode& code);
  void onTopicMessage(const TrajectoryMessage& msg);
  void push(std::unique_ptr<Command> command);

  // Real-time.
  void sampleDesired(double now) noexcept;
  void applyCommand(Command* command, double now) noexcept;
  void hold(double now) noexcept;
  void stopFollowing(GoalStatus status, TrajectoryErrorCode code, const char* reason) noexcept;
  void finishActive(GoalStatus status, TrajectoryErrorCode code, int joint = -1,
                    const char* reason = nullptr) noexcept;
  void checkTolerances(double now) noexcept;
  void writeFeedback(double now) noexcept;
  bool desiredFinite(std::size_t& joint) const noexcept;
  void reportDropped(double kind, double a, double b) noexcept;
  // Non-real-time: goals of the command not taken yet when the controller is
  // stopped or gone.
  static void abortPending(Command* command, const char* reason) noexcept;

  std::string controller_name_;
  std::string command_topic_;
  std::vector<std::string> joint_names_;
  std::vector<JointPositionError> position_errors_;  // per joint: wrapping of continuous joints
  std::vector<bool> continuous_;
  TrajectoryTolerances default_tolerances_;
  double stop_trajectory_duration_ = 0.0;
  double action_monitor_rate_ = 20.0;
  bool allow_partial_joints_goal_ = false;

  servoloop::realtime::RealtimeHandoff<Command> handoff_;
  std::mutex push_mutex_;  // one pusher at a time (never taken on the real-time thread)
  servoloop::realtime::Subscription command_subscription_;
  servoloop::realtime::RealtimePublisher<StateMessage> state_publisher_;
  // Real-time drops, logged on the bus's delivery thread: data = {kind, a, b}
  // (1: in the past, a = end time, b = control time; 2: non-finite desired
  // state, a = joint index, b = control time).
  servoloop::realtime::RealtimePublisher<servoloop::std_msgs::Float64MultiArray> dropped_publisher_;
  servoloop::realtime::Subscription dropped_reporter_;
  PeriodicGate state_gate_;
  PeriodicGate feedback_gate_;
  std::shared_ptr<GoalFeedback> goal_feedback_ = std::make_shared<GoalFeedback>();
  servoloop::realtime::ActionRegistration action_registration_;

  // Shared with the non-real-time side.
  std::atomic<bool> running_{false};
  std::atomic<bool> stopped_warning_logged_{false};
  std::atomic<double> last_time_{0.0};  // control time of the last update
  std::atomic<std::uint64_t> taken_{0};
  std::atomic<std::uint64_t> refused_{0};
  std::atomic<std::uint64_t> in_the_past_{0};
  std::atomic<std::uint64_t> non_finite_{0};

  // Controller-thread state.
  Command* active_ = nullptr;  // null: holding
  std::vector<SplineSegment> hold_;
  std::vector<JointSample> desired_;
  std::vector<JointSample> error_;
  std::vector<JointSample> actual_;
  std::vector<JointSample> current_;  // scratch: the desired state handed to a new trajectory
};

}  // namespace servoloop::controllers::joint_trajectory_controller
