#include "servoloop/controllers/joint_trajectory_controller/joint_trajectory_controller.hpp"

#include <type_traits>

#include "servoloop/controllers/common/controller_params.hpp"
#include "servoloop/controllers/common/joint_handles.hpp"
#include "servoloop/plugin/plugin_register.hpp"

namespace servoloop::controllers::joint_trajectory_controller {

namespace hi = hardware_interface;

namespace {
template <class Interface>
constexpr bool kUsesPid = !std::is_same_v<Interface, hi::PositionJointInterface>;
template <class Interface>
constexpr bool kVelocity = std::is_same_v<Interface, hi::VelocityJointInterface>;
}  // namespace

template <class Interface>
bool JointTrajectoryController<Interface>::init(Interface* hw, const controller_manager::ControllerContext& context) {
  const std::vector<std::string> joint_names = requireStringList(context, "joints", "joints: [joint1, joint2]");
  const std::size_t n = joint_names.size();
  if constexpr (kUsesPid<Interface>) {
    pids_ = std::make_unique<Pid[]>(n);
    tunable_pids_.clear();
    for (std::size_t j = 0; j < n; ++j) {
      const std::string key = "gains/" + joint_names[j];
      if (context.params.child(key).empty()) {
        throw ConfigError("controller '" + context.name + "': parameter '" + parameterPath(context, key) +
                          "' is missing; a trajectory controller on a velocity or effort interface needs PID "
                          "gains for every joint, e.g. 'gains: {" + joint_names[j] + ": {p: 100, d: 10}}'");
      }
      pids_[j].initFromParams(context.params.child(key), parameterPath(context, key));
      tunable_pids_.push_back({key, &pids_[j]});
    }
  }
  velocity_ff_.assign(n, 0.0);
  if constexpr (kVelocity<Interface>) {
    for (std::size_t j = 0; j < n; ++j) {
      velocity_ff_[j] = optionalNumber(context, "velocity_ff/" + joint_names[j], 0.0);
    }
  }
  follower_.init(context, joint_names);
  joints_ = getJointHandles(*hw, joint_names, context, "joints");
  positions_.assign(n, 0.0);
  velocities_.assign(n, 0.0);
  commands_.assign(n, 0.0);
  return true;
}

template <class Interface>
void JointTrajectoryController<Interface>::readState() noexcept {
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    positions_[j] = joints_[j].getPosition();
    velocities_[j] = joints_[j].getVelocity();
  }
}

template <class Interface>
void JointTrajectoryController<Interface>::starting(const Time& time) {
  readState();
  if constexpr (kUsesPid<Interface>) {
    for (std::size_t j = 0; j < joints_.size(); ++j) pids_[j].reset();
  }
  follower_.start(time, positions_, velocities_);
}

template <class Interface>
void JointTrajectoryController<Interface>::stopping(const Time& /*time*/) {
  follower_.stop();
  if constexpr (kUsesPid<Interface>) {
    for (std::size_t j = 0; j < joints_.size(); ++j) {
      commands_[j] = 0.0;
      joints_[j].setCommand(0.0);
    }
  }
}

template <class Interface>
void JointTrajectoryController<Interface>::setSafeOutput() {
  follower_.stopForFault();
}

template <class Interface>
ReturnType JointTrajectoryController<Interface>::update(const Time& time, const Duration& period) {
  readState();
  follower_.update(time, period, positions_, velocities_);
  const std::vector<JointSample>& desired = follower_.desired();
  const std::vector<JointSample>& error = follower_.error();
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    if constexpr (kUsesPid<Interface>) {
      commands_[j] = velocity_ff_[j] * desired[j].velocity +
                     pids_[j].computeCommand(error[j].position, error[j].velocity, period.seconds);
    } else {
      commands_[j] = desired[j].position;
    }
    joints_[j].setCommand(commands_[j]);
  }
  follower_.publishStateIfDue(time, period);
  return ReturnType::ok;
}

template class JointTrajectoryController<hi::PositionJointInterface>;
template class JointTrajectoryController<hi::VelocityJointInterface>;
template class JointTrajectoryController<hi::EffortJointInterface>;

}  // namespace servoloop::controllers::joint_trajectory_controller

SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::joint_trajectory_controller::PositionJointTrajectoryController,
                          servoloop::controller_manager::ControllerBase,
                          "position_controllers/JointTrajectoryController")
SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::joint_trajectory_controller::VelocityJointTrajectoryController,
                          servoloop::controller_manager::ControllerBase,
                          "velocity_controllers/JointTrajectoryController")
SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::joint_trajectory_controller::EffortJointTrajectoryController,
                          servoloop::controller_manager::ControllerBase,
                          "effort_controllers/JointTrajectoryController")
