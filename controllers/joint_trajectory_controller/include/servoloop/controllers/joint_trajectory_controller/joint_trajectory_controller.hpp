#pragma once
// position_controllers/, velocity_controllers/ and
// effort_controllers/JointTrajectoryController: follow joint trajectories
// (trajectory_msgs/JointTrajectory) as ros_controllers' controllers of those
// names do, with their parameters, so a ROS robot's controller YAML loads
// unchanged.
//
// Parameters (under <robot ns>/<controller>):
//   joints                      required list, the joints to drive
//   gains/<joint>               velocity and effort: required PID gains
//                               (p, i, d, i_clamp, antiwindup, as control_toolbox)
//   velocity_ff/<joint>         velocity: feed-forward factor of the desired velocity (default 0)
//   constraints                 goal_time, stopped_velocity_tolerance, <joint>: {trajectory, goal}
//   stop_trajectory_duration    s to come to rest on a stop, cancel or abort (default 0)
//   state_publish_rate          Hz of the state topic (default 50)
//   action_monitor_rate         Hz of goal feedback (default 20)
//   allow_partial_joints_goal   whether a trajectory may leave joints out (they hold; default false)
// Topics:
//   <robot ns>/<controller>/command  trajectory_msgs/JointTrajectory in
//   <robot ns>/<controller>/state    control_msgs/JointTrajectoryControllerState out
// Each update the follower (trajectory_follower.hpp) gives the desired state
// and the error desired - actual; the joint command is then
//   position: the desired position;
//   velocity: velocity_ff · desired velocity + PID(position error, velocity error);
//   effort:   PID(position error, velocity error).
// Stopping the controller sets velocity and effort commands to 0. Stopping it
// in any way (a switch, a fault, unloading) aborts its goal with the reason.
#include <memory>
#include <string>
#include <vector>

#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/controllers/joint_trajectory_controller/trajectory_follower.hpp"
#include "servoloop/controllers/pid.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"

namespace servoloop::controllers::joint_trajectory_controller {

template <class Interface>
class JointTrajectoryController : public controller_manager::Controller<Interface> {
 public:
  // Non-real-time. Throws servoloop::ConfigError naming the parameter.
  bool init(Interface* hw, const controller_manager::ControllerContext& context) override;
  // Real-time.
  void starting(const Time& time) override;
  void stopping(const Time& time) override;
  // Real-time: stopped for a fault (the manager wrote the safe commands):
  // the follower stops and its goal is aborted with the reason.
  void setSafeOutput() override;
  ReturnType update(const Time& time, const Duration& period) override;
  // Non-real-time: on velocity and effort interfaces, each joint's PID as "gains/<joint>".
  std::vector<controller_manager::TunablePid> tunablePids() override { return tunable_pids_; }

  TrajectoryFollower& follower() noexcept { return follower_; }
  // Controller thread, or once it stopped (tests and diagnostics).
  const std::vector<double>& commands() const noexcept { return commands_; }

 private:
  void readState() noexcept;

  TrajectoryFollower follower_;
  std::vector<typename Interface::Handle> joints_;
  std::unique_ptr<Pid[]> pids_;      // velocity and effort
  std::vector<controller_manager::TunablePid> tunable_pids_;  // pids_ as "gains/<joint>"
  std::vector<double> velocity_ff_;  // velocity
  std::vector<double> positions_;
  std::vector<double> velocities_;
  std::vector<double> commands_;
};

using PositionJointTrajectoryController = JointTrajectoryController<hardware_interface::PositionJointInterface>;
using VelocityJointTrajectoryController = JointTrajectoryController<hardware_interface::VelocityJointInterface>;
using EffortJointTrajectoryController = JointTrajectoryController<hardware_interface::EffortJointInterface>;

extern template class JointTrajectoryController<hardware_interface::PositionJointInterface>;
extern template class JointTrajectoryController<hardware_interface::VelocityJointInterface>;
extern template class JointTrajectoryController<hardware_interface::EffortJointInterface>;

}  // namespace servoloop::controllers::joint_trajectory_controller
