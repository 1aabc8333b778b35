#include "servoloop/sim_mujoco/mujoco_physics.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <string_view>

#include <mujoco/mujoco.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/sim_common/ground_penetration.hpp"
#include "servoloop/sim_mujoco/mjcf_from_urdf.hpp"
#include "servoloop/sim_mujoco/mujoco_world.hpp"
#include "mjcf_compile.hpp"
#include "model_step.hpp"

namespace servoloop::sim_mujoco {
namespace {

using sim_common::JointCommandMode;

// Projected Gauss-Seidel sweeps for several coupled motors (one motor is
// solved exactly in one sweep); stops early once the efforts settle.
constexpr int kMotorSolverSweeps = 50;
constexpr double kMotorSolverTolerance = 1e-12;

}  // namespace

void MujocoPhysics::ModelDeleter::operator()(mjModel_* model) const noexcept { mj_deleteModel(model); }
void MujocoPhysics::DataDeleter::operator()(mjData_* data) const noexcept { mj_deleteData(data); }

MujocoPhysics::MujocoPhysics() = default;
MujocoPhysics::~MujocoPhysics() {
  if (world_ != nullptr && m_ != nullptr) world_->remove(*this);
}

void MujocoPhysics::joinWorld(hardware_interface::SimulatedWorld& world) {
  auto* shared = dynamic_cast<MujocoWorld*>(&world);
  if (shared == nullptr) {
    sim_common::PhysicsEngine::joinWorld(world);  // robots apart: a model of its own
    return;
  }
  world_ = shared;
}

// MuJoCo's free joint: qpos = position, quaternion (w, x, y, z) of the body
// frame; qvel = linear velocity of its origin in world axes, then angular
// velocity in the body's own axes.
bool MujocoPhysics::readBaseState(sim_common::EngineBaseState& out) const noexcept {
  if (base_qpos_address_ < 0 || !d_) return false;
  const double* q = d_->qpos + base_qpos_address_;
  const double* v = d_->qvel + base_dof_address_;
  out.position = Eigen::Vector3d(q[0], q[1], q[2]);
  out.orientation = Eigen::Quaterniond(q[3], q[4], q[5], q[6]).normalized();
  out.linear_velocity = Eigen::Vector3d(v[0], v[1], v[2]);
  out.angular_velocity = out.orientation * Eigen::Vector3d(v[3], v[4], v[5]);
  return true;
}

void MujocoPhysics::setBaseState(const sim_common::EngineBaseState& state) {
  if (base_qpos_address_ < 0 || !d_) sim_common::PhysicsEngine::setBaseState(state);
  double* q = d_->qpos + base_qpos_address_;
  double* v = d_->qvel + base_dof_address_;
  const Eigen::Quaterniond orientation = state.orientation.normalized();
  const Eigen::Vector3d angular_in_body = orientation.conjugate() * state.angular_velocity;
  for (int i = 0; i < 3; ++i) {
    q[i] = state.position[i];
    v[i] = state.linear_velocity[i];
    v[3 + i] = angular_in_body[i];
  }
  q[3] = orientation.w();
  q[4] = orientation.x();
  q[5] = orientation.y();
  q[6] = orientation.z();
  mj_forward(m_, d_);
}

void MujocoPhysics::init(const urdf::ModelInterface& model, const sim_common::SimSettings& settings,
                         const std::vector<sim_common::EngineJointConfig>& joints, const std::string& source_name) {
  std::map<std::string, double> armature;
  for (const auto& joint : joints) armature[joint.name] = joint.reflected_rotor_inertia;
  joint_names_.clear();
  for (const auto& joint : joints) joint_names_.push_back(joint.name);
  initial_positions_.clear();
  for (const auto& joint : joints) initial_positions_.push_back(joint.initial_position);
  motor_limits_.clear();
  for (const auto& joint : joints) motor_limits_.push_back(sim_common::motorEffortBound(joint));
  resizeJointCommands(joints.size());
  robot_name_ = model.getName();
  joint_child_links_.clear();
  for (const auto& [name, joint] : model.joints_) joint_child_links_[name] = joint->child_link_name;
  position_motor_time_constant_s_ = std::max(kPositionMotorTimeConstant_s, settings.time_step_s);
  if (world_ != nullptr) {
    prefix_ = world_->newPrefix();
    base_joint_name_ = prefix_ + model.getRoot()->name + "_floating_base";
    world_->add(*this, mjcfPartsFromUrdf(model, settings, armature, source_name, prefix_), source_name,
                model.getName());
    mjcf_ = world_->mjcf();
  } else {
    base_joint_name_ = model.getRoot()->name + "_floating_base";
    mjcf_ = mjcfFromUrdf(model, settings, armature, source_name);
    data_.reset();
    model_.reset(compileMjcf(mjcf_, source_name));
    data_.reset(mj_makeData(model_.get()));
    if (!data_) throw Error(source_name + ": MuJoCo could not allocate its simulation data");
    bind(model_.get(), data_.get());
  }
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    const int id = mj_name2id(m_, mjOBJ_JOINT, (prefix_ + joint_names_[j]).c_str());
    if (id < 0 || (m_->jnt_type[id] != mjJNT_HINGE && m_->jnt_type[id] != mjJNT_SLIDE)) {
      throw ConfigError(source_name + ": joint '" + joint_names_[j] +
                        "' is not a revolute, continuous or prismatic joint of the robot");
    }
  }
  reset();
  warnOfGroundPenetration(model, settings, source_name);
  if (world_ != nullptr) warnOfOverlap(source_name);
}

// After reset()'s mj_forward the contacts of the spawn pose are known: the
// deepest between one of this robot's bodies and another robot's.
void MujocoPhysics::warnOfOverlap(const std::string& source_name) const {
  const mjModel& m = *m_;
  const mjData& d = *d_;
  const auto prefixOf = [](std::string_view body) {
    const std::size_t slash = body.find('/');
    return slash == std::string_view::npos ? std::string() : std::string(body.substr(0, slash + 1));
  };
  double depth_m = 0.0;
  std::string link;
  std::string other;
  for (int i = 0; i < d.ncon; ++i) {
    const mjContact& contact = d.contact[i];
    const char* first = mj_id2name(&m, mjOBJ_BODY, m.geom_bodyid[contact.geom1]);
    const char* second = mj_id2name(&m, mjOBJ_BODY, m.geom_bodyid[contact.geom2]);
    if (first == nullptr || second == nullptr) continue;
    std::string own = first;
    std::string foreign = second;
    if (prefixOf(own) != prefix_) std::swap(own, foreign);
    const std::string foreign_prefix = prefixOf(foreign);
    if (prefixOf(own) != prefix_ || foreign_prefix.empty() || foreign_prefix == prefix_) continue;
    if (-contact.dist > depth_m) {
      depth_m = -contact.dist;
      link = own.substr(prefix_.size());
      other = "robot '" + world_->robotName(foreign_prefix) + "' link '" + foreign.substr(foreign_prefix.size()) + "'";
    }
  }
  if (depth_m > sim_common::kGroundPenetrationWarningDepth_m) {
    logger().warn(
        "{}: link '{}' starts {:.3f} m inside {} at its spawn pose; the contact pushes the two apart with a jolt at "
        "the first step. Spawn it elsewhere (launch file: pose: [x, y, z]; spawn-model: -x -y -z)",
        source_name, link, depth_m, other);
  }
}

void MujocoPhysics::bind(mjModel_* model, mjData_* data) {
  m_ = model;
  d_ = data;
  const mjModel& m = *m_;
  const int base = base_joint_name_.empty() ? -1 : mj_name2id(&m, mjOBJ_JOINT, base_joint_name_.c_str());
  base_qpos_address_ = base >= 0 ? m.jnt_qposadr[base] : -1;
  base_dof_address_ = base >= 0 ? m.jnt_dofadr[base] : -1;
  joints_.assign(joint_names_.size(), Joint{});
  for (std::size_t j = 0; j < joint_names_.size(); ++j) {
    const int id = mj_name2id(&m, mjOBJ_JOINT, (prefix_ + joint_names_[j]).c_str());
    if (id < 0) continue;  // init() names it
    joints_[j].qpos_address = m.jnt_qposadr[id];
    joints_[j].dof_address = m.jnt_dofadr[id];
    joints_[j].motor_effort_limit = motor_limits_[j];
  }
  own_joints_.clear();
  for (int j = 0; j < m.njnt; ++j) {
    const char* name = mj_id2name(&m, mjOBJ_JOINT, j);
    if (name == nullptr || std::string_view(name).substr(0, prefix_.size()) != prefix_) continue;
    const int qpos_count = m.jnt_type[j] == mjJNT_FREE ? 7 : m.jnt_type[j] == mjJNT_BALL ? 4 : 1;
    const int dof_count = m.jnt_type[j] == mjJNT_FREE ? 6 : m.jnt_type[j] == mjJNT_BALL ? 3 : 1;
    own_joints_.push_back(OwnJoint{m.jnt_qposadr[j], qpos_count, m.jnt_dofadr[j], dof_count});
  }
  const std::size_t count = joints_.size();
  const std::size_t nv = static_cast<std::size_t>(m.nv);
  motor_joints_.assign(count, 0);
  unit_forces_.assign(count * nv, 0.0);
  inverse_inertia_.assign(count * nv, 0.0);
  wanted_accel_.assign(count, 0.0);
  motor_efforts_.assign(count, 0.0);
  bindSensors();
}

// After reset()'s mj_forward the contacts of the start pose are known: the
// deepest one of a link with the ground plane (MuJoCo's dist < 0 is overlap).
void MujocoPhysics::warnOfGroundPenetration(const urdf::ModelInterface& model,
                                           const sim_common::SimSettings& settings,
                                           const std::string& source_name) const {
  const mjModel& m = *m_;
  const mjData& d = *d_;
  const int ground = mj_name2id(&m, mjOBJ_GEOM, "servoloop_ground_plane");
  if (ground < 0) return;
  double depth_m = 0.0;
  int deepest_body = -1;
  for (int i = 0; i < d.ncon; ++i) {
    const mjContact& contact = d.contact[i];
    if (contact.geom1 != ground && contact.geom2 != ground) continue;
    const int other = contact.geom1 == ground ? contact.geom2 : contact.geom1;
    const char* body = mj_id2name(&m, mjOBJ_BODY, m.geom_bodyid[other]);
    if (body == nullptr || std::string_view(body).substr(0, prefix_.size()) != prefix_) continue;  // another robot's
    if (-contact.dist > depth_m) {
      depth_m = -contact.dist;
      deepest_body = m.geom_bodyid[other];
    }
  }
  if (deepest_body < 0) return;
  const char* link = mj_id2name(&m, mjOBJ_BODY, deepest_body);
  const std::string link_name = link != nullptr ? std::string(link).substr(prefix_.size()) : "?";
  sim_common::warnIfStartsBelowGround(model, settings, source_name, link_name, depth_m);
}

void MujocoPhysics::placeAtInitialPositions() {
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    d_->qpos[joints_[j].qpos_address] = initial_positions_[j];
    d_->qvel[joints_[j].dof_address] = 0.0;
  }
  mj_forward(m_, d_);
}

double MujocoPhysics::jointPosition(std::size_t joint) const noexcept {
  return d_->qpos[joints_[joint].qpos_address];
}

double MujocoPhysics::jointVelocity(std::size_t joint) const noexcept {
  return d_->qvel[joints_[joint].dof_address];
}

void MujocoPhysics::step() noexcept {
  mjData& d = *d_;
  // Efforts for this step; the motors' are solved below.
  std::size_t motors = 0;
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    Joint& joint = joints_[j];
    const sim_common::AppliedJointCommand& command = jointCommand(j);
    const bool motor = command.mode == JointCommandMode::velocity || command.mode == JointCommandMode::position;
    joint.applied_effort = motor ? 0.0 : command.value;
    d.qfrc_applied[joint.dof_address] = joint.applied_effort;
    if (motor) motor_joints_[motors++] = j;
  }
  if (motors > 0) solveMotorEfforts(motors);

  // Alone, the robot steps its model; in a world, the world steps it.
  if (world_ == nullptr) {
    if (hasSensors()) {
      stepModel(m_, &d, [this]() noexcept { captureSensorData(); });
    } else {
      mj_step(m_, &d);
    }
  }

  endEffortCommands();
}

// The motor efforts u (one per motor-driven joint) that give each motor its
// wanted velocity at the end of the step, v + dt·(a_free + M⁻¹u) = v_wanted,
// with |u| within each motor's bound. a_free is the acceleration of every
// other force (gravity, Coriolis, damping, stops, contacts, effort
// commands) at the start of the step.
void MujocoPhysics::solveMotorEfforts(std::size_t motors) noexcept {
  const mjModel& m = *m_;
  mjData& d = *d_;
  const std::size_t nv = static_cast<std::size_t>(m.nv);
  const double dt = m.opt.timestep;

  // a_free, and the mass matrix factorised (with armature), at the current state.
  mj_forward(&m, &d);
  // Columns of M⁻¹ for the motor dofs: M x_k = e_k.
  std::fill(unit_forces_.begin(), unit_forces_.begin() + static_cast<std::ptrdiff_t>(motors * nv), 0.0);
  for (std::size_t k = 0; k < motors; ++k) {
    unit_forces_[k * nv + static_cast<std::size_t>(joints_[motor_joints_[k]].dof_address)] = 1.0;
  }
  mj_solveM(&m, &d, inverse_inertia_.data(), unit_forces_.data(), static_cast<int>(motors));
  const auto inverse_inertia = [&](std::size_t row, std::size_t column) {  // M⁻¹ between two motors
    return inverse_inertia_[column * nv + static_cast<std::size_t>(joints_[motor_joints_[row]].dof_address)];
  };

  for (std::size_t k = 0; k < motors; ++k) {
    const Joint& joint = joints_[motor_joints_[k]];
    const sim_common::AppliedJointCommand& command = jointCommand(motor_joints_[k]);
    const double velocity = d.qvel[joint.dof_address];
    const double wanted_velocity = command.mode == JointCommandMode::velocity
                                       ? command.value
                                       : (command.value - d.qpos[joint.qpos_address]) / position_motor_time_constant_s_;
    // The extra acceleration the motor must add to what the other forces give.
    wanted_accel_[k] = (wanted_velocity - velocity) / dt - d.qacc[joint.dof_address];
    motor_efforts_[k] = 0.0;
  }
  // Projected Gauss-Seidel on M⁻¹_SS u = wanted, |u_k| <= bound_k: exact in
  // one sweep for a single motor, converging for several (M⁻¹_SS is positive definite).
  for (int sweep = 0; sweep < kMotorSolverSweeps; ++sweep) {
    double largest_change = 0.0;
    double largest_effort = 0.0;
    for (std::size_t k = 0; k < motors; ++k) {
      double accel = 0.0;
      for (std::size_t i = 0; i < motors; ++i) accel += inverse_inertia(k, i) * motor_efforts_[i];
      const double bound = joints_[motor_joints_[k]].motor_effort_limit;
      const double updated =
          std::clamp(motor_efforts_[k] + (wanted_accel_[k] - accel) / inverse_inertia(k, k), -bound, bound);
      largest_change = std::max(largest_change, std::abs(updated - motor_efforts_[k]));
      motor_efforts_[k] = updated;
      largest_effort = std::max(largest_effort, std::abs(updated));
    }
    if (motors == 1 || largest_change <= kMotorSolverTolerance * (1.0 + largest_effort)) break;
  }
  for (std::size_t k = 0; k < motors; ++k) {
    Joint& joint = joints_[motor_joints_[k]];
    joint.applied_effort = motor_efforts_[k];
    d.qfrc_applied[joint.dof_address] = motor_efforts_[k];
  }
}

void MujocoPhysics::reset() {
  if (world_ == nullptr) {
    mj_resetData(m_, d_);
  } else {
    // Only this robot's share of the world: its joints at their model
    // positions (a free joint at the spawn pose), at rest.
    for (const OwnJoint& joint : own_joints_) {
      std::copy_n(m_->qpos0 + joint.qpos_address, joint.qpos_count, d_->qpos + joint.qpos_address);
      std::fill_n(d_->qvel + joint.dof_address, joint.dof_count, 0.0);
      std::fill_n(d_->qacc_warmstart + joint.dof_address, joint.dof_count, 0.0);
      std::fill_n(d_->qfrc_applied + joint.dof_address, joint.dof_count, 0.0);
    }
  }
  clearJointCommands();
  for (Joint& joint : joints_) joint.applied_effort = 0.0;
  for (sim_common::EngineJointWrench& wrench : joint_wrenches_) wrench = {};
  placeAtInitialPositions();
}

void MujocoPhysics::setJointState(std::size_t joint, double position, double velocity) {
  d_->qpos[joints_.at(joint).qpos_address] = position;
  d_->qvel[joints_.at(joint).dof_address] = velocity;
  mj_forward(m_, d_);
}

std::array<double, 3> MujocoPhysics::linkWorldPosition(const std::string& link_name) const {
  const int body = link_name == "world" ? 0 : mj_name2id(m_, mjOBJ_BODY, (prefix_ + link_name).c_str());
  if (body < 0) throw Error("MuJoCo world: no link '" + link_name + "' in the robot");
  const mjtNum* position = d_->xpos + 3 * body;
  return {position[0], position[1], position[2]};
}

int MujocoPhysics::contactCount() const noexcept { return d_ != nullptr ? d_->ncon : 0; }

double MujocoPhysics::time() const noexcept { return d_ != nullptr ? d_->time : 0.0; }

}  // namespace servoloop::sim_mujoco
