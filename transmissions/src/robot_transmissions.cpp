#include "servoloop/transmissions/robot_transmissions.hpp"

#include <urdf_parser/urdf_parser.h>

#include <cassert>
#include <string_view>
#include <utility>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/transmissions/simple_transmission.hpp"
#include "servoloop/transmissions/transmission_parser.hpp"
#include "urdf_joint_kind.hpp"

namespace servoloop::transmissions {
namespace {

namespace hi = hardware_interface;

JointCommandInterfaces commandInterfacesOf(const TransmissionJointInfo& joint) {
  constexpr std::string_view kPrefix = "hardware_interface/";
  JointCommandInterfaces commands;
  for (std::string_view name : joint.hardware_interfaces) {
    if (name.substr(0, kPrefix.size()) == kPrefix) name.remove_prefix(kPrefix.size());
    commands.effort |= name == "EffortJointInterface";
    commands.velocity |= name == "VelocityJointInterface";
    commands.position |= name == "PositionJointInterface";
  }
  return commands;
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
  return text.empty() ? "none" : text;
}

}  // namespace

RobotTransmissions::RobotTransmissions(const urdf::ModelInterface& robot,
                                       const std::vector<TransmissionInfo>& infos,
                                       const Options& options) {
  for (const TransmissionInfo& info : infos) addTransmission(info, robot, options);

  if (options.implicit_simple_transmissions) {
    // urdfdom keeps joints in a name-ordered map, so implicit joints come by name.
    for (const auto& [name, urdf_joint] : robot.joints_) {
      if (!urdf_joint || !detail::isSingleDofMovable(*urdf_joint) || hasJoint(name)) continue;
      // A mimic joint follows its leader through the physics; it is not
      // actuated on its own (it gets an actuator only from a <transmission>).
      if (urdf_joint->mimic) continue;
      TransmissionInfo info;
      info.name = name + "_implicit_transmission";
      info.type = kSimpleTransmissionType;
      // Every joint command interface: the controller that claims the joint
      // chooses effort, velocity or position (a diff drive's wheels take velocity).
      const std::vector<std::string> interfaces{"EffortJointInterface", "VelocityJointInterface",
                                                "PositionJointInterface"};
      info.joints.push_back({name, interfaces, "", 1.0, 0.0});
      info.actuators.push_back({name + "_motor", interfaces, "", 1.0});
      addTransmission(info, robot, options);
      implicit_joints_.push_back(name);
    }
    if (!implicit_joints_.empty()) {
      logger().info(
          "{}: robot '{}': no <transmission> for joint(s) {}; using an implicit "
          "SimpleTransmission for each (reduction 1, offset 0, actuator '<joint>_motor'; effort, velocity "
          "or position, as the controller that claims it asks)",
          options.source_name, robot.getName(), joinNames(implicit_joints_));
    }
  }

  // Sized once here; everything below points into these vectors.
  joints_.assign(joint_names_.size(), JointValues{});
  actuators_.assign(actuator_names_.size(), ActuatorValues{});
  bindStorage();
  fillInterfaces();
}

RobotTransmissions::~RobotTransmissions() = default;

std::unique_ptr<RobotTransmissions> RobotTransmissions::fromUrdf(const std::string& urdf_xml,
                                                                 const Options& options) {
  std::vector<TransmissionInfo> infos = parseTransmissions(urdf_xml, options.source_name);
  // parseTransmissions has already rejected a description urdfdom cannot read.
  const urdf::ModelInterfaceSharedPtr robot = parseUrdfWithUrdfdom(urdf_xml, options.source_name, false);
  return std::make_unique<RobotTransmissions>(*robot, infos, options);
}

void RobotTransmissions::addTransmission(const TransmissionInfo& info,
                                         const urdf::ModelInterface& robot,
                                         const Options& options) {
  const std::string where = options.source_name + ": transmission '" + info.name + "': ";
  std::vector<std::size_t> joint_indices;
  std::vector<std::size_t> actuator_indices;
  JointCommandInterfaces transmission_commands;

  for (const TransmissionJointInfo& joint : info.joints) {
    const urdf::JointConstSharedPtr urdf_joint = robot.getJoint(joint.name);
    if (!urdf_joint || !detail::isSingleDofMovable(*urdf_joint)) {
      throw ConfigError(where + "joint '" + joint.name + "' is not a revolute, continuous or " +
                        "prismatic joint of robot '" + robot.getName() +
                        "'; fix the joint name in the <transmission>");
    }
    if (hasJoint(joint.name)) {
      throw ConfigError(where + "joint '" + joint.name +
                        "' is already driven by another transmission; each joint may appear "
                        "in one transmission only");
    }
    const JointCommandInterfaces commands = commandInterfacesOf(joint);
    transmission_commands.effort |= commands.effort;
    transmission_commands.velocity |= commands.velocity;
    transmission_commands.position |= commands.position;
    joint_index_.emplace(joint.name, joint_names_.size());
    joint_indices.push_back(joint_names_.size());
    joint_names_.push_back(joint.name);
    joint_commands_.push_back(commands);
  }
  for (const TransmissionActuatorInfo& actuator : info.actuators) {
    if (hasActuator(actuator.name)) {
      throw ConfigError(where + "actuator '" + actuator.name +
                        "' is already used by another transmission; give each actuator a "
                        "unique name");
    }
    actuator_index_.emplace(actuator.name, actuator_names_.size());
    actuator_indices.push_back(actuator_names_.size());
    actuator_names_.push_back(actuator.name);
  }

  Binding binding;
  binding.name = info.name;
  try {
    binding.transmission = makeTransmission(info);
  } catch (const ConfigError& e) {
    throw ConfigError(options.source_name + ": " + e.what());
  }
  binding.commands = transmission_commands;
  bindings_.push_back(std::move(binding));
  binding_joints_.push_back(std::move(joint_indices));
  binding_actuators_.push_back(std::move(actuator_indices));
}

void RobotTransmissions::bindStorage() {
  for (std::size_t b = 0; b < bindings_.size(); ++b) {
    Binding& binding = bindings_[b];
    const auto* simple = dynamic_cast<const SimpleTransmission*>(binding.transmission.get());
    if (simple != nullptr && binding_joints_[b].size() == 1 && binding_actuators_[b].size() == 1) {
      simple_bindings_.push_back(SimpleBinding{binding_joints_[b][0], binding_actuators_[b][0], simple->reduction(),
                                               simple->jointOffset(), binding.commands});
    } else {
      general_bindings_.push_back(&binding);
    }
    for (const std::size_t j : binding_joints_[b]) {
      JointValues& values = joints_[j];
      binding.joint_state.position.push_back(&values.position);
      binding.joint_state.velocity.push_back(&values.velocity);
      binding.joint_state.effort.push_back(&values.effort);
      binding.joint_command.position.push_back(&values.position_command);
      binding.joint_command.velocity.push_back(&values.velocity_command);
      binding.joint_command.effort.push_back(&values.effort_command);
    }
    for (const std::size_t a : binding_actuators_[b]) {
      ActuatorValues& values = actuators_[a];
      binding.actuator_state.position.push_back(&values.position);
      binding.actuator_state.velocity.push_back(&values.velocity);
      binding.actuator_state.effort.push_back(&values.effort);
      binding.actuator_command.position.push_back(&values.position_command);
      binding.actuator_command.velocity.push_back(&values.velocity_command);
      binding.actuator_command.effort.push_back(&values.effort_command);
    }
  }
}

void RobotTransmissions::fillInterfaces() {
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    JointValues& values = joints_[j];
    const hi::JointStateHandle state(joint_names_[j], &values.position, &values.velocity,
                                     &values.effort);
    joint_state_interface_.registerHandle(state);
    const JointCommandInterfaces& commands = joint_commands_[j];
    if (commands.effort) {
      effort_joint_interface_.registerHandle(hi::JointHandle(state, &values.effort_command));
    }
    if (commands.velocity) {
      velocity_joint_interface_.registerHandle(hi::JointHandle(state, &values.velocity_command));
    }
    if (commands.position) {
      position_joint_interface_.registerHandle(hi::JointHandle(state, &values.position_command));
    }
  }
  for (std::size_t b = 0; b < bindings_.size(); ++b) {
    const JointCommandInterfaces& commands = bindings_[b].commands;
    for (const std::size_t a : binding_actuators_[b]) {
      ActuatorValues& values = actuators_[a];
      const hi::ActuatorStateHandle state(actuator_names_[a], &values.position, &values.velocity,
                                          &values.effort);
      actuator_state_interface_.registerHandle(state);
      if (commands.effort) {
        effort_actuator_interface_.registerHandle(
            hi::ActuatorHandle(state, &values.effort_command));
      }
      if (commands.velocity) {
        velocity_actuator_interface_.registerHandle(
            hi::ActuatorHandle(state, &values.velocity_command));
      }
      if (commands.position) {
        position_actuator_interface_.registerHandle(
            hi::ActuatorHandle(state, &values.position_command));
      }
    }
  }
}

void RobotTransmissions::registerInterfaces(hardware_interface::InterfaceManager& manager) {
  manager.registerInterface(&joint_state_interface_);
  manager.registerInterface(&actuator_state_interface_);
  // A command interface no joint names stays unregistered, so a controller
  // asking for it learns the hardware does not offer it.
  if (!effort_joint_interface_.getNames().empty()) {
    manager.registerInterface(&effort_joint_interface_);
    manager.registerInterface(&effort_actuator_interface_);
  }
  if (!velocity_joint_interface_.getNames().empty()) {
    manager.registerInterface(&velocity_joint_interface_);
    manager.registerInterface(&velocity_actuator_interface_);
  }
  if (!position_joint_interface_.getNames().empty()) {
    manager.registerInterface(&position_joint_interface_);
    manager.registerInterface(&position_actuator_interface_);
  }
}

void RobotTransmissions::actuatorStateToJointState() noexcept {
  for (const SimpleBinding& b : simple_bindings_) {
    const ActuatorValues& actuator = actuators_[b.actuator];
    JointValues& joint = joints_[b.joint];
    joint.position = SimpleTransmission::jointPosition(actuator.position, b.reduction, b.joint_offset);
    joint.velocity = SimpleTransmission::jointVelocity(actuator.velocity, b.reduction);
    joint.effort = SimpleTransmission::jointEffort(actuator.effort, b.reduction);
  }
  for (Binding* b : general_bindings_) {
    b->transmission->actuatorToJointPosition(b->actuator_state, b->joint_state);
    b->transmission->actuatorToJointVelocity(b->actuator_state, b->joint_state);
    b->transmission->actuatorToJointEffort(b->actuator_state, b->joint_state);
  }
}

void RobotTransmissions::generalJointCommandToActuatorCommand() noexcept {
  for (Binding* b : general_bindings_) {
    if (b->commands.effort) b->transmission->jointToActuatorEffort(b->joint_command, b->actuator_command);
    if (b->commands.velocity) b->transmission->jointToActuatorVelocity(b->joint_command, b->actuator_command);
    if (b->commands.position) b->transmission->jointToActuatorPosition(b->joint_command, b->actuator_command);
  }
}

void RobotTransmissions::generalJointStateToActuatorState() noexcept {
  for (Binding* b : general_bindings_) {
    b->transmission->jointToActuatorPosition(b->joint_state, b->actuator_state);
    b->transmission->jointToActuatorVelocity(b->joint_state, b->actuator_state);
    b->transmission->jointToActuatorEffort(b->joint_state, b->actuator_state);
  }
}

void RobotTransmissions::actuatorEffortToJointEffort() noexcept {
  for (const SimpleBinding& b : simple_bindings_) {
    joints_[b.joint].effort_command =
        SimpleTransmission::jointEffort(actuators_[b.actuator].effort_command, b.reduction);
  }
  for (Binding* b : general_bindings_) b->transmission->actuatorToJointEffort(b->actuator_command, b->joint_command);
}

void RobotTransmissions::actuatorVelocityToJointVelocity() noexcept {
  for (const SimpleBinding& b : simple_bindings_) {
    joints_[b.joint].velocity_command =
        SimpleTransmission::jointVelocity(actuators_[b.actuator].velocity_command, b.reduction);
  }
  for (Binding* b : general_bindings_) {
    b->transmission->actuatorToJointVelocity(b->actuator_command, b->joint_command);
  }
}

void RobotTransmissions::actuatorPositionToJointPosition() noexcept {
  for (const SimpleBinding& b : simple_bindings_) {
    joints_[b.joint].position_command =
        SimpleTransmission::jointPosition(actuators_[b.actuator].position_command, b.reduction, b.joint_offset);
  }
  for (Binding* b : general_bindings_) {
    b->transmission->actuatorToJointPosition(b->actuator_command, b->joint_command);
  }
}

void RobotTransmissions::actuatorCommandToJointCommand() noexcept {
  for (const SimpleBinding& b : simple_bindings_) {
    const ActuatorValues& actuator = actuators_[b.actuator];
    JointValues& joint = joints_[b.joint];
    if (b.commands.effort) joint.effort_command = SimpleTransmission::jointEffort(actuator.effort_command, b.reduction);
    if (b.commands.velocity) {
      joint.velocity_command = SimpleTransmission::jointVelocity(actuator.velocity_command, b.reduction);
    }
    if (b.commands.position) {
      joint.position_command =
          SimpleTransmission::jointPosition(actuator.position_command, b.reduction, b.joint_offset);
    }
  }
  for (Binding* b : general_bindings_) {
    if (b->commands.effort) b->transmission->actuatorToJointEffort(b->actuator_command, b->joint_command);
    if (b->commands.velocity) b->transmission->actuatorToJointVelocity(b->actuator_command, b->joint_command);
    if (b->commands.position) b->transmission->actuatorToJointPosition(b->actuator_command, b->joint_command);
  }
}

JointIndex RobotTransmissions::jointIndex(const std::string& name) const {
  const auto it = joint_index_.find(name);
  if (it == joint_index_.end()) {
    throw ConfigError("joint '" + name +
                      "' has no transmission (joints with one: " + joinNames(joint_names_) +
                      "); check the joint name, or add a <transmission> for it to the URDF");
  }
  return JointIndex(it->second);
}

ActuatorIndex RobotTransmissions::actuatorIndex(const std::string& name) const {
  const auto it = actuator_index_.find(name);
  if (it == actuator_index_.end()) {
    throw ConfigError("actuator '" + name + "' is not in any transmission (actuators: " +
                      joinNames(actuator_names_) + "); check the <actuator name> in the URDF");
  }
  return ActuatorIndex(it->second);
}

}  // namespace servoloop::transmissions
