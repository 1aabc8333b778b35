#include "servoloop/controllers/joint_trajectory_controller/follow_joint_trajectory_action.hpp"

#include "servoloop/controllers/joint_trajectory_controller/trajectory_follower.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/realtime/action_messages.hpp"

namespace servoloop::controllers::joint_trajectory_controller {
namespace {

namespace cm = servoloop::control_msgs;

std::vector<JointToleranceOverride> overrides(const std::vector<cm::JointTolerance>& tolerances) {
  std::vector<JointToleranceOverride> out;
  for (const auto& t : tolerances) out.push_back({t.name, t.position, t.velocity, t.acceleration});
  return out;
}

// A goal as its sender sees it. Holds what it reads, not the controller, so
// it may outlive the controller.
class TrajectoryActionGoal : public servoloop::realtime::ActionGoal {
 public:
  TrajectoryActionGoal(std::shared_ptr<TrajectoryGoal> goal, std::shared_ptr<TrajectoryFollower::GoalFeedback> feedback)
      : goal_(std::move(goal)), feedback_(std::move(feedback)) {}

  servoloop::realtime::GoalState state() const override { return goal_->status(); }
  void cancel() override { goal_->requestCancel(); }
  bool feedback(void* out) const override {
    std::lock_guard lock(feedback_->mutex);
    if (feedback_->goal != goal_.get()) return false;
    *static_cast<cm::FollowJointTrajectoryFeedback*>(out) = feedback_->feedback;
    return true;
  }
  void result(void* out) const override {
    auto& result = *static_cast<cm::FollowJointTrajectoryResult*>(out);
    result.error_code = static_cast<int>(goal_->errorCode());
    result.error_string = goal_->errorString();
  }
  std::string statusText() const override { return goal_->errorString(); }

 private:
  std::shared_ptr<TrajectoryGoal> goal_;
  std::shared_ptr<TrajectoryFollower::GoalFeedback> feedback_;
};

}  // namespace

std::shared_ptr<servoloop::realtime::ActionGoal> FollowJointTrajectoryAction::sendGoal(const void* goal_message) {
  const auto& message = *static_cast<const cm::FollowJointTrajectoryGoal*>(goal_message);
  std::shared_ptr<TrajectoryGoal> goal;
  try {
    TrajectoryTolerances tolerances =
        applyGoalTolerances(follower_.defaultTolerances(), follower_.jointNames(), overrides(message.path_tolerance),
                            overrides(message.goal_tolerance), message.goal_time_tolerance);
    goal = follower_.submitGoal(message.trajectory, std::move(tolerances));
  } catch (const Error& e) {
    goal = std::make_shared<TrajectoryGoal>(follower_.defaultTolerances());
    goal->reject(TrajectoryErrorCode::invalid_goal, e.what());
  }
  return std::make_shared<TrajectoryActionGoal>(std::move(goal), follower_.goalFeedback());
}

}  // namespace servoloop::controllers::joint_trajectory_controller
