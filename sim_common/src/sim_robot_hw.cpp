#include "servoloop/sim_common/sim_robot_hw.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>

#include <fmt/format.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/description/simulatable_urdf.hpp"
#include "servoloop/description/xacro.hpp"
#include "servoloop/sim_common/contact_friction.hpp"
#include "servoloop/transmissions/transmission_parser.hpp"

namespace servoloop::sim_common {

namespace hi = hardware_interface;

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The joint command mode an interface name selects, accepting the
// "hardware_interface/" and "hardware_interface::" spellings too. Returns
// false for names that are not joint command interfaces.
bool jointModeOfInterface(std::string_view name, JointCommandMode& mode) noexcept {
  for (std::string_view prefix : {"hardware_interface::", "hardware_interface/"}) {
    if (name.substr(0, prefix.size()) == prefix) name.remove_prefix(prefix.size());
  }
  if (name == "EffortJointInterface") mode = JointCommandMode::effort;
  else if (name == "VelocityJointInterface") mode = JointCommandMode::velocity;
  else if (name == "PositionJointInterface") mode = JointCommandMode::position;
  else return false;
  return true;
}

bool isActuatorCommandInterface(std::string_view name) noexcept {
  for (std::string_view prefix : {"hardware_interface::", "hardware_interface/"}) {
    if (name.substr(0, prefix.size()) == prefix) name.remove_prefix(prefix.size());
  }
  return name == "EffortActuatorInterface" || name == "VelocityActuatorInterface" ||
         name == "PositionActuatorInterface";
}

bool offers(const transmissions::JointCommandInterfaces& offered, JointCommandMode mode) {
  switch (mode) {
    case JointCommandMode::effort: return offered.effort;
    case JointCommandMode::velocity: return offered.velocity;
    case JointCommandMode::position: return offered.position;
    case JointCommandMode::none: return true;
  }
  return false;
}

}  // namespace

const char* toString(JointCommandMode mode) noexcept {
  switch (mode) {
    case JointCommandMode::none: return "none";
    case JointCommandMode::effort: return "effort";
    case JointCommandMode::velocity: return "velocity";
    case JointCommandMode::position: return "position";
  }
  return "?";
}

SimRobotHW::SimRobotHW(std::unique_ptr<PhysicsEngine> engine) : engine_(std::move(engine)) {
  if (!engine_) throw Error("SimRobotHW: no physics engine given");
}

SimRobotHW::~SimRobotHW() = default;

void SimRobotHW::init(const hi::HardwareInfo& info) {
  if (transmissions_) throw Error("SimRobotHW::init: called twice; create a new hardware object");
  const std::string& ns = info.robot_namespace;

  // Robot description and its transmissions (implicit ones for joints without).
  loadModel(info);

  // Joint limits: URDF, overridden by <ns>/joint_limits.
  joint_limits_ = hi::loadRobotJointLimits(*model_, info.parameters, ns);

  // World settings and motor parameters.
  settings_ = parseSimSettings(info.parameters, *model_, ns, urdf_self_collide_);
  settings_.link_friction = std::move(urdf_link_friction_);
  checkBase(ns);
  configureActuators(ns, info.parameters);

  // Per-joint tables, sized once: nothing on the real-time path resizes them.
  const std::size_t joint_count = transmissions_->numJoints();
  modes_.assign(joint_count, JointCommandMode::none);
  applied_.assign(joint_count, AppliedJointCommand{});
  estop_positions_.assign(joint_count, 0.0);
  engine_states_.assign(joint_count, EngineJointState{});
  limiters_.clear();
  limiters_.reserve(joint_count);
  for (std::size_t j = 0; j < joint_count; ++j) {
    const JointIndex index(j);
    const std::string& name = transmissions_->jointName(index);
    const auto limits_it = joint_limits_.find(name);
    limiters_.emplace_back(name, transmissions_->joint(index),
                           transmissions_->jointCommandInterfaces(index),
                           limits_it == joint_limits_.end() ? nullptr : &limits_it->second);
  }

  configureEngineJoints();
  engine_->init(*model_, settings_, engine_joints_, source_name_);
  transmissions_->registerInterfaces(*this);
  readEngineState();
  initSensors();
  logger().info("{}: '{}' simulation of robot '{}' ready: {} joint(s), {} actuator(s), time step {} s",
                source_name_, engine_->name(), model_->getName(), joint_count,
                transmissions_->numActuators(), settings_.time_step_s);
}

// A root link without mass fixes the base (pybullet's static-base
// convention); say so, since a URDF alone does not show it. A floating base
// needs a mass.
void SimRobotHW::checkBase(const std::string& ns) const {
  const urdf::LinkConstSharedPtr root = model_->getRoot();
  const bool root_has_mass = rigidBodyMass(*root) > 0.0;
  if (!isFixedBase(*model_, settings_.base) && !root_has_mass) {
    throw ConfigError(source_name_ + ": root link '" + root->name + "' (with the links fixed to it) has no mass but " + ns +
                      "/sim/fixed_base is false; give the root link an <inertial> with <mass> > 0, or fix the base");
  }
  if (settings_.base != BaseMode::automatic || root->name == "world" || !isFixedBase(*model_, settings_.base)) return;
  logger().info(
      "{}: root link '{}' has no mass, so the base is fixed in the world (pybullet's convention for a static "
      "base); to let it float, give it an <inertial> and set {}/sim/fixed_base: false",
      source_name_, root->name, ns);
}

void SimRobotHW::loadModel(const hi::HardwareInfo& info) {
  source_name_ = info.urdf_path.empty() ? std::string("robot_description") : info.urdf_path;
  std::string xml = info.urdf_xml;
  if (xml.empty()) {
    if (info.urdf_path.empty()) {
      throw ConfigError("simulation: no robot description given (neither URDF text nor a URDF path)");
    }
    xml = readRobotDescription(info.urdf_path);
  }
  xml = simulatableUrdf(xml, source_name_).xml;
  urdf_self_collide_ = urdfRequestsSelfCollision(xml);
  model_ = parseRobotModel(xml, source_name_);
  urdf_link_friction_ = urdfLinkFriction(xml, *model_, source_name_);
  sensor_descriptions_ = readGazeboSensors(xml, *model_, source_name_);
  transmissions::RobotTransmissions::Options options;
  options.implicit_simple_transmissions = true;
  options.source_name = source_name_;
  transmissions_ = std::make_unique<transmissions::RobotTransmissions>(
      *model_, transmissions::parseTransmissions(xml, source_name_), options);
}

void SimRobotHW::initSensors() {
  if (sensor_descriptions_.empty()) return;
  if (!engine_->simulatesSensors()) {
    logger().warn("{}: the {} engine does not simulate sensors; the robot's {} sensor(s) are left out (the bullet "
                  "and mujoco backends simulate them)",
                  source_name_, engine_->name(), sensor_descriptions_.size());
    return;
  }
  sensors_.init(sensor_descriptions_, *model_, *engine_, settings_.gravity, source_name_);
  sensors_.registerInterfaces(*this);
}

void SimRobotHW::configureActuators(const std::string& ns, const YAML::Node& parameters) {
  std::vector<std::string> actuator_names;
  for (std::size_t a = 0; a < transmissions_->numActuators(); ++a) {
    actuator_names.push_back(transmissions_->actuatorName(ActuatorIndex(a)));
  }
  const auto by_name = parseActuatorParameters(parameters, actuator_names, ns);
  actuator_parameters_.clear();
  for (const std::string& name : actuator_names) actuator_parameters_.push_back(by_name.at(name));
  any_motor_limit_ = std::any_of(actuator_parameters_.begin(), actuator_parameters_.end(),
                                 [](const ActuatorParameters& p) { return std::isfinite(p.max_effort); });
}

// The transmissions are linear in velocity: actuator velocity = T · joint
// velocity. Power balance then gives joint effort = Tᵀ · actuator effort, so a
// joint's motors can deliver at most Σ_a |T[a][j]|·max_effort_a, and the rotor
// inertias appear at the joint as Tᵀ·diag(J)·T, whose diagonal Σ_a J_a·T[a][j]²
// is what we add (the off-diagonal couplings of two-joint transmissions are
// left out). T is measured by pushing unit joint velocities through the maps:
// every joint at rest, then each in turn at unit velocity, back at rest once
// its column is read (the maps only read the joints), so that a column costs
// one pass of the maps and not also a reset of every joint.
void SimRobotHW::configureEngineJoints() {
  transmissions::RobotTransmissions& tr = *transmissions_;
  const std::size_t joint_count = tr.numJoints();
  const std::size_t actuator_count = tr.numActuators();
  engine_joints_.assign(joint_count, EngineJointConfig{});
  for (std::size_t k = 0; k < joint_count; ++k) tr.joint(JointIndex(k)) = transmissions::JointValues{};
  for (std::size_t j = 0; j < joint_count; ++j) {
    tr.joint(JointIndex(j)).velocity = 1.0;
    tr.jointStateToActuatorState();
    tr.joint(JointIndex(j)) = transmissions::JointValues{};

    double motor_bound = 0.0;
    double reflected_inertia = 0.0;
    for (std::size_t a = 0; a < actuator_count; ++a) {
      const double ratio = tr.actuator(ActuatorIndex(a)).velocity;  // T[a][j]
      if (ratio == 0.0) continue;
      motor_bound += std::abs(ratio) * actuator_parameters_[a].max_effort;
      reflected_inertia += actuator_parameters_[a].rotor_inertia * ratio * ratio;
    }
    EngineJointConfig& config = engine_joints_[j];
    config.name = tr.jointName(JointIndex(j));
    config.motor_effort_limit = motor_bound > 0.0 ? motor_bound : kInfinity;
    const auto limits_it = joint_limits_.find(config.name);
    if (limits_it != joint_limits_.end() && limits_it->second.limits.has_effort_limits) {
      config.motor_effort_limit = std::min(config.motor_effort_limit, limits_it->second.limits.max_effort);
    }
    config.reflected_rotor_inertia = reflected_inertia;
    const auto initial_it = settings_.initial_positions.find(config.name);
    config.initial_position = initial_it == settings_.initial_positions.end() ? 0.0 : initial_it->second;
    if (limits_it != joint_limits_.end()) warnAboutLimits(config, limits_it->second.limits);
  }
  for (std::size_t k = 0; k < joint_count; ++k) tr.joint(JointIndex(k)) = transmissions::JointValues{};
  for (std::size_t a = 0; a < actuator_count; ++a) tr.actuator(ActuatorIndex(a)) = transmissions::ActuatorValues{};
}

// Limits that leave a joint stuck are legal URDF; say what they do.
void SimRobotHW::warnAboutLimits(const EngineJointConfig& joint, const hi::JointLimits& limits) const {
  if (limits.has_effort_limits && limits.max_effort == 0.0) {
    logger().warn(
        "{}: joint '{}' has an effort limit of 0 (<limit effort=\"0\"> or joint_limits max_effort): every "
        "command to it is held to zero effort, so it cannot be driven; give it a positive effort limit",
        source_name_, joint.name);
  }
  if (limits.has_position_limits &&
      (joint.initial_position < limits.min_position || joint.initial_position > limits.max_position)) {
    logger().warn(
        "{}: joint '{}' starts at {} outside its position limits [{}, {}]; the limits push it back at the first "
        "step; set <ns>/sim/initial_positions/{} to a position inside them",
        source_name_, joint.name, joint.initial_position, limits.min_position, limits.max_position, joint.name);
  }
}

bool SimRobotHW::readBaseGroundTruth(hi::BaseGroundTruth& out) const noexcept {
  EngineBaseState base;
  if (!engine_ || !engine_->readBaseState(base)) return false;
  for (int i = 0; i < 3; ++i) {
    out.position[i] = base.position[i];
    out.linear_velocity[i] = base.linear_velocity[i];
    out.angular_velocity[i] = base.angular_velocity[i];
  }
  out.orientation[0] = base.orientation.x();
  out.orientation[1] = base.orientation.y();
  out.orientation[2] = base.orientation.z();
  out.orientation[3] = base.orientation.w();
  return true;
}

void SimRobotHW::setBaseState(const hi::BaseGroundTruth& state) {
  if (!engine_) throw Error("SimRobotHW::setBaseState: call init() first");
  EngineBaseState probe;
  if (!engine_->readBaseState(probe)) {
    throw Error(fmt::format("{}: the robot's base is fixed to the world (at its spawn pose, <ns>/sim/pose); only a "
                            "floating base can be moved. Give the robot another sim/pose and reset the world, or "
                            "spawn it elsewhere",
                            source_name_));
  }
  const auto finite = [](const double* values, int count) {
    return std::all_of(values, values + count, [](double v) { return std::isfinite(v); });
  };
  if (!finite(state.position, 3) || !finite(state.orientation, 4) || !finite(state.linear_velocity, 3) ||
      !finite(state.angular_velocity, 3)) {
    throw Error(fmt::format("{}: every value of the pose and twist must be a finite number", source_name_));
  }
  Eigen::Quaterniond orientation(state.orientation[3], state.orientation[0], state.orientation[1],
                                 state.orientation[2]);
  if (!(orientation.norm() > 1e-9)) {
    throw Error(fmt::format("{}: the orientation quaternion (x y z w) is zero; give a rotation, e.g. 0 0 0 1",
                            source_name_));
  }
  EngineBaseState base;
  base.position = Eigen::Vector3d(state.position[0], state.position[1], state.position[2]);
  base.orientation = orientation.normalized();
  base.linear_velocity = Eigen::Vector3d(state.linear_velocity[0], state.linear_velocity[1], state.linear_velocity[2]);
  base.angular_velocity =
      Eigen::Vector3d(state.angular_velocity[0], state.angular_velocity[1], state.angular_velocity[2]);
  engine_->setBaseState(base);
  readEngineState();
}

void SimRobotHW::readEngineState() noexcept {
  transmissions::RobotTransmissions& tr = *transmissions_;
  engine_->readJointStates(engine_states_);
  for (std::size_t j = 0; j < engine_states_.size(); ++j) {
    const EngineJointState& state = engine_states_[j];
    transmissions::JointValues& joint = tr.joint(JointIndex(j));
    joint.position = state.position;
    joint.velocity = state.velocity;
    joint.effort = state.effort;
  }
  // The motors measure the joints through the transmissions. Mapping their
  // readings back would give the same joint state (the maps are invertible),
  // so controllers see the engine's joint state directly.
  tr.jointStateToActuatorState();
}

ReturnType SimRobotHW::read(Time /*time*/, Duration /*period*/) {
  readEngineState();
  if (!sensors_.empty()) sensors_.update(simTime().seconds);
  return ReturnType::ok;
}

ReturnType SimRobotHW::write(Time /*time*/, Duration period) {
  // The every-cycle path; emergency stops and motor effort limits are out of line.
  transmissions::RobotTransmissions& tr = *transmissions_;
  const std::size_t joint_count = applied_.size();
  const bool estop = estop_requested_.load(std::memory_order_acquire);
  if (estop != estop_active_) [[unlikely]] changeEmergencyStop(estop);

  // Joint limits on the commands controllers wrote, before anything else sees them.
  for (std::size_t j = 0; j < joint_count; ++j) limiters_[j].enforce(modes_[j], period);

  // Through the motors: joint → actuator, motor effort limits, actuator →
  // joint. Without motor limits the way back would return the joint commands
  // unchanged, so it is only taken when a limit may have cut an actuator's.
  tr.jointCommandToActuatorCommand();
  if (any_motor_limit_) [[unlikely]] limitMotorEfforts();

  if (estop_active_) [[unlikely]] {
    applyEmergencyStop();
    return ReturnType::ok;
  }
  // What the engine applies at the next step. Non-finite commands (from a
  // joint without limit handles) become harmless: no effort, no motion.
  for (std::size_t j = 0; j < joint_count; ++j) {
    const transmissions::JointValues& joint = tr.joint(JointIndex(j));
    AppliedJointCommand& applied = applied_[j];
    const JointCommandMode mode = modes_[j];
    applied.mode = mode;
    switch (mode) {
      case JointCommandMode::none:
        applied.value = 0.0;
        break;
      case JointCommandMode::effort:
        applied.value = std::isfinite(joint.effort_command) ? joint.effort_command : 0.0;
        break;
      case JointCommandMode::velocity:
        applied.value = std::isfinite(joint.velocity_command) ? joint.velocity_command : 0.0;
        break;
      case JointCommandMode::position:
        applied.value = std::isfinite(joint.position_command) ? joint.position_command : joint.position;
        break;
    }
  }
  return ReturnType::ok;
}

void SimRobotHW::changeEmergencyStop(bool engaged) noexcept {
  // Engaged: remember where the joints were; released: the limit handles
  // start again from the measured state.
  if (engaged) {
    for (std::size_t j = 0; j < applied_.size(); ++j) estop_positions_[j] = transmissions_->joint(JointIndex(j)).position;
  } else {
    for (JointCommandLimiter& limiter : limiters_) limiter.reset();
  }
  estop_active_ = engaged;
}

void SimRobotHW::limitMotorEfforts() noexcept {
  transmissions::RobotTransmissions& tr = *transmissions_;
  for (std::size_t a = 0; a < actuator_parameters_.size(); ++a) {
    const double max_effort = actuator_parameters_[a].max_effort;
    double& effort_command = tr.actuator(ActuatorIndex(a)).effort_command;
    if (std::isfinite(max_effort) && std::isfinite(effort_command)) {
      effort_command = std::clamp(effort_command, -max_effort, max_effort);
    }
  }
  tr.actuatorCommandToJointCommand();
}

void SimRobotHW::applyEmergencyStop() noexcept {
  // Position commands hold where the joints were when the stop engaged;
  // effort and velocity commands are zero.
  for (std::size_t j = 0; j < applied_.size(); ++j) {
    AppliedJointCommand& applied = applied_[j];
    applied.mode = modes_[j];
    applied.value = modes_[j] == JointCommandMode::position ? estop_positions_[j] : 0.0;
  }
}

ReturnType SimRobotHW::step() {
  engine_->applyJointCommands(applied_);
  engine_->step();
  ++steps_;
  return ReturnType::ok;
}

bool SimRobotHW::prepareSwitch(const std::vector<hi::ControllerInfo>& start_list,
                               const std::vector<hi::ControllerInfo>& /*stop_list*/) {
  for (const hi::ControllerInfo& controller : start_list) {
    for (const hi::InterfaceResources& claimed : controller.claimed_resources) {
      if (isActuatorCommandInterface(claimed.hardware_interface)) {
        logger().error(
            "{}: controller '{}' claims {} ({}); the simulation takes commands through joint "
            "interfaces only (EffortJointInterface, VelocityJointInterface, PositionJointInterface)",
            source_name_, controller.name, claimed.hardware_interface,
            claimed.resources.empty() ? std::string() : *claimed.resources.begin());
        return false;
      }
      JointCommandMode mode = JointCommandMode::none;
      if (!jointModeOfInterface(claimed.hardware_interface, mode)) continue;
      for (const std::string& resource : claimed.resources) {
        if (!transmissions_->hasJoint(resource)) {
          logger().error("{}: controller '{}' claims joint '{}', which this robot does not have",
                         source_name_, controller.name, resource);
          return false;
        }
        const JointIndex joint = transmissions_->jointIndex(resource);
        if (!offers(transmissions_->jointCommandInterfaces(joint), mode)) {
          logger().error(
              "{}: controller '{}' claims joint '{}' through {}, which the joint's <transmission> "
              "does not name; add that <hardwareInterface> to it",
              source_name_, controller.name, resource, claimed.hardware_interface);
          return false;
        }
      }
    }
  }
  return true;
}

void SimRobotHW::applyModesFromClaims(const hi::ControllerInfo& controller, bool starting) noexcept {
  for (const hi::InterfaceResources& claimed : controller.claimed_resources) {
    JointCommandMode mode = JointCommandMode::none;
    if (!jointModeOfInterface(claimed.hardware_interface, mode)) continue;
    for (const std::string& resource : claimed.resources) {
      if (!transmissions_->hasJoint(resource)) continue;  // prepareSwitch refused those
      const std::size_t j = transmissions_->jointIndex(resource).value();
      modes_[j] = starting ? mode : JointCommandMode::none;
      if (starting) limiters_[j].reset();
    }
  }
}

ReturnType SimRobotHW::doSwitch(const std::vector<hi::ControllerInfo>& start_list,
                                const std::vector<hi::ControllerInfo>& stop_list) {
  for (const hi::ControllerInfo& controller : stop_list) applyModesFromClaims(controller, false);
  for (const hi::ControllerInfo& controller : start_list) applyModesFromClaims(controller, true);
  return ReturnType::ok;
}

void SimRobotHW::setJointCommandMode(JointIndex joint, JointCommandMode mode) noexcept {
  modes_[joint.value()] = mode;
  limiters_[joint.value()].reset();
}

JointCommandMode SimRobotHW::jointCommandMode(JointIndex joint) const noexcept {
  return modes_[joint.value()];
}

AppliedJointCommand SimRobotHW::appliedCommand(JointIndex joint) const noexcept {
  return applied_[joint.value()];
}

LimitEnforcement SimRobotHW::limitEnforcement(JointIndex joint, JointCommandMode mode) const noexcept {
  return limiters_[joint.value()].enforcement(mode);
}

Duration SimRobotHW::timeStep() const { return Duration(settings_.time_step_s); }

Time SimRobotHW::simTime() const {
  return Time(static_cast<double>(steps_) * settings_.time_step_s);
}

void SimRobotHW::zeroCommands() noexcept {
  transmissions::RobotTransmissions& tr = *transmissions_;
  for (std::size_t j = 0; j < tr.numJoints(); ++j) {
    transmissions::JointValues& joint = tr.joint(JointIndex(j));
    joint.effort_command = joint.velocity_command = joint.position_command = 0.0;
  }
  for (std::size_t a = 0; a < tr.numActuators(); ++a) {
    transmissions::ActuatorValues& actuator = tr.actuator(ActuatorIndex(a));
    actuator.effort_command = actuator.velocity_command = actuator.position_command = 0.0;
  }
  for (AppliedJointCommand& applied : applied_) applied = AppliedJointCommand{};
}

void SimRobotHW::reset() {
  if (!transmissions_) throw Error("SimRobotHW::reset: call init() first");
  engine_->reset();
  zeroCommands();
  for (JointCommandLimiter& limiter : limiters_) limiter.reset();
  steps_ = 0;
  readEngineState();
  sensors_.reset(0.0);
  if (estop_active_) {
    for (std::size_t j = 0; j < applied_.size(); ++j) {
      estop_positions_[j] = transmissions_->joint(JointIndex(j)).position;
    }
  }
}

void SimRobotHW::setJointPositions(const std::vector<std::string>& joints, const std::vector<double>& positions) {
  if (!transmissions_) throw Error("SimRobotHW::setJointPositions: call init() first");
  if (joints.size() != positions.size()) {
    throw Error(fmt::format("{}: {} joint names but {} positions; give one position per joint", source_name_,
                            joints.size(), positions.size()));
  }
  std::vector<std::size_t> indices;
  for (std::size_t k = 0; k < joints.size(); ++k) {
    indices.push_back(transmissions_->jointIndex(joints[k]).value());
    if (!std::isfinite(positions[k])) {
      throw Error(fmt::format("{}: position {} of joint '{}' is not a finite number", source_name_, positions[k],
                              joints[k]));
    }
  }
  for (std::size_t k = 0; k < joints.size(); ++k) engine_->setJointState(indices[k], positions[k], 0.0);
  readEngineState();
  if (estop_active_) {
    for (const std::size_t j : indices) estop_positions_[j] = transmissions_->joint(JointIndex(j)).position;
  }
}

void SimRobotHW::setEmergencyStop(bool engaged) {
  estop_requested_.store(engaged, std::memory_order_release);
}

}  // namespace servoloop::sim_common
