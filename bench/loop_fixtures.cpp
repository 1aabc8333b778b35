#include "loop_fixtures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "bench_support.hpp"
#include "servoloop/hardware_interface/hardware_info.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/description/robot_model.hpp"

namespace servoloop::bench {

namespace cm = controller_manager;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
namespace hi = hardware_interface;

YAML::Node RobotCase::namespaceParams() const { return YAML::LoadFile(sourcePath(params))[params_key]; }

RobotCase seedRobot() {
  RobotCase robot;
  robot.label = "seed";
  robot.urdf = "robots/one_dof/minimal_robot_description_w_jnt_ctl.urdf";
  robot.params = "robots/one_dof/control_config/one_dof_ctl_params.yaml";
  robot.params_key = "one_DOF_robot";
  robot.position_controllers = {"joint1_position_controller"};
  robot.joints = {"joint1"};
  robot.setpoints_rad = {1.0};
  robot.steps_per_episode = 10000;
  return robot;
}

RobotCase chainRobot(bool group) {
  RobotCase robot;
  robot.label = group ? "chain32_group" : "chain32";
  robot.urdf = "robots/chain32/chain32.urdf";
  robot.params = "robots/chain32/control_config/chain32_controllers.yaml";
  robot.params_key = "chain32";
  robot.joints = numberedJointNames(32);
  for (std::size_t i = 0; i < robot.joints.size(); ++i) {
    robot.setpoints_rad.push_back(0.2 * std::sin(2.0 * M_PI * static_cast<double>(i) / 16.0));
    if (!group) robot.position_controllers.push_back(robot.joints[i] + "_position_controller");
  }
  if (group) robot.group_controller = "arm_position_controller";
  robot.steps_per_episode = 2000;
  return robot;
}

HandWrittenPositionLaw HandWrittenPositionLaw::forJoint(const RobotCase& robot, const YAML::Node& params,
                                                        std::size_t i, const urdf::ModelInterface& model) {
  const YAML::Node pid = robot.group_controller.empty() ? params[robot.position_controllers[i]]["pid"]
                                                        : params[robot.group_controller][robot.joints[i]]["pid"];
  const auto gain = [&pid](const char* key) { return pid[key] ? pid[key].as<double>() : 0.0; };
  HandWrittenPositionLaw law;
  law.setpoint_rad = robot.setpoints_rad[i];
  law.kp = gain("p");
  law.ki = gain("i");
  law.kd = gain("d");
  // As the PID reads them: i_clamp sets both bounds, the one-sided keys win.
  law.i_min = -std::abs(gain("i_clamp"));
  law.i_max = std::abs(gain("i_clamp"));
  if (pid["i_clamp_min"]) law.i_min = -std::abs(gain("i_clamp_min"));
  if (pid["i_clamp_max"]) law.i_max = std::abs(gain("i_clamp_max"));
  const urdf::JointConstSharedPtr joint = model.getJoint(robot.joints[i]);
  if (!joint) throw std::runtime_error("no joint '" + robot.joints[i] + "' in " + robot.urdf);
  const urdf::JointLimitsSharedPtr& limits = joint->limits;
  law.effort_limit = limits && limits->effort > 0.0 ? limits->effort : kInfinity;
  const bool bounded = joint->type != urdf::Joint::CONTINUOUS && limits;
  law.lower = bounded ? limits->lower : -kInfinity;
  law.upper = bounded ? limits->upper : kInfinity;
  law.velocity_limit = limits && limits->velocity > 0.0 ? limits->velocity : kInfinity;
  return law;
}

RawBulletPd::RawBulletPd(const RobotCase& robot) : model_(loadRobotModelFile(sourcePath(robot.urdf))) {
  sim_bullet::WorldSettings settings;
  settings.time_step_s = kTimeStepS;
  world_ = std::make_unique<sim_bullet::BulletWorld>(*model_, settings);
  const YAML::Node params = robot.namespaceParams();
  for (std::size_t i = 0; i < robot.joints.size(); ++i) {
    joints_.push_back({world_->jointIndex(robot.joints[i]), HandWrittenPositionLaw::forJoint(robot, params, i, *model_)});
  }
}

void RawBulletPd::step() noexcept {
  sim_bullet::BulletWorld& world = *world_;
  for (Joint& joint : joints_) {
    const double effort = joint.law.effort(world.jointPosition(joint.index), world.jointVelocity(joint.index));
    world.setJointEffort(joint.index, effort);
  }
  world.step();
}

void RawBulletPd::stepWithoutControl() noexcept {
  for (const Joint& joint : joints_) world_->setJointEffort(joint.index, 0.0);
  world_->step();
}

double RawBulletPd::maxAbsJointPosition() const {
  double largest = 0.0;
  for (const Joint& joint : joints_) largest = std::max(largest, std::abs(world_->jointPosition(joint.index)));
  return largest;
}

double RawBulletPd::jointPosition(std::size_t controlled_joint) const {
  return world_->jointPosition(joints_[controlled_joint].index);
}

ServoloopSimulation::ServoloopSimulation(const RobotCase& robot, const std::string& backend)
    : loader_({pluginDirectory()}) {
  hw_ = loader_.create<hi::RobotHW>(backend);
  auto* simulated = dynamic_cast<hi::SimulatedRobotHW*>(hw_.get());
  if (simulated == nullptr) throw std::runtime_error(backend + " is not a simulated robot_hw");
  const YAML::Node params = robot.namespaceParams();
  hi::HardwareInfo info;
  info.urdf_path = sourcePath(robot.urdf);
  info.urdf_xml = readTextFile(info.urdf_path);
  info.robot_namespace = robot.robotNamespace();
  info.parameters = params;
  hw_->init(info);

  cm::ControllerContext context;
  context.robot_namespace = robot.robotNamespace();
  context.topics = &bus_;
  context.robot_model = parseRobotModel(info.urdf_xml, info.urdf_path);
  manager_ = std::make_unique<cm::ControllerManager>(hw_.get(), std::make_shared<PluginControllerFactory>(),
                                                     cm::ControllerManager::lookupIn(params), context,
                                                     kManagerRateHz);
  std::vector<std::string> controllers = {"joint_state_controller"};
  if (robot.group_controller.empty()) {
    controllers.insert(controllers.end(), robot.position_controllers.begin(), robot.position_controllers.end());
  } else {
    controllers.push_back(robot.group_controller);
  }
  for (const auto& name : controllers) {
    if (auto result = manager_->loadController(name); !result) throw std::runtime_error(result.message);
  }
  cm::SwitchRequest request;
  request.start_controllers = controllers;
  if (auto result = manager_->requestSwitch(request); !result) throw std::runtime_error(result.message);

  cm::SimulationLoop::Options options;
  options.topic_bus = &bus_;
  loop_ = std::make_unique<cm::SimulationLoop>(*simulated, *manager_, options);
  loop_->cycleOnce();  // carries out the switch (the raw loop takes one step too)
  if (manager_->switchPending()) throw std::runtime_error("the controller switch did not happen");

  const std::string prefix = robot.robotNamespace() + "/";
  if (robot.group_controller.empty()) {
    for (std::size_t i = 0; i < robot.position_controllers.size(); ++i) {
      bus_.publish(prefix + robot.position_controllers[i] + "/command", servoloop::std_msgs::Float64{robot.setpoints_rad[i]});
    }
  } else {
    bus_.publish(prefix + robot.group_controller + "/command", servoloop::std_msgs::Float64MultiArray{robot.setpoints_rad});
  }
  bus_.flush();  // the setpoints reach the controllers before the first timed cycle, as in the raw loop
  first_joint_ = hw_->get<hi::JointStateInterface>()->getHandle(robot.joints.front());
  bus_.start();
}

ServoloopSimulation::~ServoloopSimulation() {
  bus_.stop();
  loop_.reset();
  manager_.reset();
}

void ServoloopSimulation::runSteps(std::uint64_t steps) {
  loop_->runFor(Duration(static_cast<double>(steps) * kTimeStepS));
}

std::uint64_t ServoloopSimulation::hardwareErrors() const { return loop_->statistics().snapshot().hardware_errors; }

}  // namespace servoloop::bench
