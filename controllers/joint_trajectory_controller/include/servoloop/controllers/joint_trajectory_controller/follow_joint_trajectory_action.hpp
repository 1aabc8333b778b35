#pragma once
// The follow_joint_trajectory action (control_msgs/FollowJointTrajectory) of
// a joint trajectory controller: a goal's trajectory and tolerances become a
// TrajectoryGoal of the controller's follower; its state, feedback and result
// are read from there. A goal whose tolerances name joints the controller
// lacks is rejected (INVALID_GOAL) before it reaches the follower.
#include <memory>

#include "servoloop/realtime/action_registry.hpp"

namespace servoloop::controllers::joint_trajectory_controller {

class TrajectoryFollower;

class FollowJointTrajectoryAction : public servoloop::realtime::ActionServer {
 public:
  // follower must outlive the action's registration (it owns it).
  explicit FollowJointTrajectoryAction(TrajectoryFollower& follower) : follower_(follower) {}
  std::shared_ptr<servoloop::realtime::ActionGoal> sendGoal(const void* goal) override;

 private:
  TrajectoryFollower& follower_;
};

}  // namespace servoloop::controllers::joint_trajectory_controller
