#pragma once
// RobotTransmissions: the one place where a robot's actuator space and joint
// space meet, used alike by the simulation backends and by real hardware.
//
// Data flow. RobotTransmissions owns every value of both spaces, allocated once
// at construction and never resized (so handles and pointers into it stay valid
// for its whole life; it is neither copyable nor movable):
//
//   actuator space (motor side)                  joint space (load side)
//   ActuatorValues per actuator                  JointValues per joint
//   position / velocity / effort      ──read──▶  position / velocity / effort
//     actuatorStateToJointState()                  (JointStateInterface → controllers)
//   effort_ / velocity_ / position_command ◀─write─ effort_ / velocity_ / position_command
//     jointCommandToActuatorCommand()              (Effort/Velocity/PositionJointInterface)
//
// Real hardware fills the actuator state from its drivers in read(), calls
// actuatorStateToJointState(), lets the controllers run on the joint handles,
// calls jointCommandToActuatorCommand() and sends the actuator commands in
// write(). A simulator measures joints rather than motors, so it goes the
// other way as well: it writes the measured joint state and calls
// jointStateToActuatorState() (so actuator-space readers see consistent
// values), and maps the actuator commands back to what it applies to its
// joints with actuatorEffortToJointEffort() (or the velocity/position
// variants). Applied to a command that came from the joint side, the round
// trip joint → actuator → joint is the identity up to rounding, but reductions
// and offsets are honoured for commands written in actuator space.
//
// Every propagation method runs on the real-time thread: it only walks
// pre-built tables and calls the transmissions' maps (no allocation, no locks,
// no logging, no exceptions). SimpleTransmissions, the common case, are kept
// in a flat table of (joint, actuator, n, o) and mapped inline with
// SimpleTransmission's own formulas; the others through their virtual maps.
// Everything else is non-real-time.
#include <urdf_model/model.h>

#include <cassert>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "servoloop/hardware_interface/actuator_interfaces.hpp"
#include "servoloop/hardware_interface/interface_manager.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/core/strong_index.hpp"
#include "servoloop/transmissions/simple_transmission.hpp"
#include "servoloop/transmissions/transmission.hpp"
#include "servoloop/transmissions/transmission_info.hpp"

namespace servoloop::transmissions {

// One joint's state and commands, in joint space (rad or m, rad/s or m/s, N·m or N).
struct JointValues {
  double position = 0.0;
  double velocity = 0.0;
  double effort = 0.0;
  double effort_command = 0.0;
  double velocity_command = 0.0;
  double position_command = 0.0;
};

// One actuator's state and commands, in actuator space (motor side of its transmission).
struct ActuatorValues {
  double position = 0.0;
  double velocity = 0.0;
  double effort = 0.0;
  double effort_command = 0.0;
  double velocity_command = 0.0;
  double position_command = 0.0;
};

// Which command interfaces a joint offers, from its <hardwareInterface> list.
struct JointCommandInterfaces {
  bool effort = false;
  bool velocity = false;
  bool position = false;
};

struct RobotTransmissionsOptions {
  // Give every revolute, continuous or prismatic joint that no <transmission>
  // names an implicit SimpleTransmission (reduction 1, offset 0,
  // EffortJointInterface, actuator "<joint>_motor"); mimic joints excepted,
  // since they follow their leader. Off: such joints are not part of either space.
  bool implicit_simple_transmissions = false;
  // Names the robot description in messages (usually its file name).
  std::string source_name = "URDF";
};

class RobotTransmissions {
 public:
  using Options = RobotTransmissionsOptions;

  // Non-real-time. Builds the transmissions of `infos` (as parseTransmissions
  // returns them) plus, if asked, the implicit ones; allocates all storage and
  // fills the interfaces. Joints are numbered in transmission order (then the
  // implicit joints, by name); actuators likewise. Throws servoloop::ConfigError
  // naming the source, transmission and fix for a joint the robot lacks, a
  // joint or actuator used twice, or an invalid transmission.
  RobotTransmissions(const urdf::ModelInterface& robot, const std::vector<TransmissionInfo>& infos,
                     const Options& options = {});

  // Non-real-time. Parses the robot and its transmissions from URDF text.
  static std::unique_ptr<RobotTransmissions> fromUrdf(const std::string& urdf_xml,
                                                      const Options& options = {});

  RobotTransmissions(const RobotTransmissions&) = delete;
  RobotTransmissions& operator=(const RobotTransmissions&) = delete;
  RobotTransmissions(RobotTransmissions&&) = delete;
  RobotTransmissions& operator=(RobotTransmissions&&) = delete;
  ~RobotTransmissions();

  // Non-real-time. Registers JointStateInterface (all joints),
  // Effort/Velocity/PositionJointInterface (the joints whose URDF names that
  // interface; an interface no joint names is not registered),
  // ActuatorStateInterface (all actuators) and Effort/Velocity/Position-
  // ActuatorInterface (the actuators of those joints' transmissions). The
  // interfaces are members of this object: it must outlive `manager`'s use.
  void registerInterfaces(hardware_interface::InterfaceManager& manager);

  // Real-time. Read path: joint position/velocity/effort from the actuators'.
  void actuatorStateToJointState() noexcept;
  // Real-time. Write path: for each transmission, the actuator commands for
  // the command interfaces its joints name (effort, velocity, position).
  // (Inline, as jointStateToActuatorState: the simple transmissions, which
  // most joints have, are mapped without a call.)
  void jointCommandToActuatorCommand() noexcept {
    for (const SimpleBinding& b : simple_bindings_) {
      const JointValues& joint = joints_[b.joint];
      ActuatorValues& actuator = actuators_[b.actuator];
      if (b.commands.effort) actuator.effort_command = SimpleTransmission::actuatorEffort(joint.effort_command, b.reduction);
      if (b.commands.velocity) {
        actuator.velocity_command = SimpleTransmission::actuatorVelocity(joint.velocity_command, b.reduction);
      }
      if (b.commands.position) {
        actuator.position_command =
            SimpleTransmission::actuatorPosition(joint.position_command, b.reduction, b.joint_offset);
      }
    }
    if (!general_bindings_.empty()) generalJointCommandToActuatorCommand();
  }

  // Real-time, simulation direction. Actuator position/velocity/effort from
  // the joints' (a simulator measures joints).
  void jointStateToActuatorState() noexcept {
    for (const SimpleBinding& b : simple_bindings_) {
      const JointValues& joint = joints_[b.joint];
      ActuatorValues& actuator = actuators_[b.actuator];
      actuator.position = SimpleTransmission::actuatorPosition(joint.position, b.reduction, b.joint_offset);
      actuator.velocity = SimpleTransmission::actuatorVelocity(joint.velocity, b.reduction);
      actuator.effort = SimpleTransmission::actuatorEffort(joint.effort, b.reduction);
    }
    if (!general_bindings_.empty()) generalJointStateToActuatorState();
  }
  // Real-time, simulation direction. Joint effort commands from the actuator
  // effort commands of every transmission (what a simulator applies).
  void actuatorEffortToJointEffort() noexcept;
  // Real-time, simulation direction. Joint velocity commands from actuator velocity commands.
  void actuatorVelocityToJointVelocity() noexcept;
  // Real-time, simulation direction. Joint position commands from actuator position commands.
  void actuatorPositionToJointPosition() noexcept;
  // Real-time, simulation direction. For each transmission, the joint commands
  // for the command interfaces its joints name.
  void actuatorCommandToJointCommand() noexcept;

  std::size_t numJoints() const noexcept { return joints_.size(); }
  std::size_t numActuators() const noexcept { return actuators_.size(); }
  std::size_t numTransmissions() const noexcept { return bindings_.size(); }

  const std::string& jointName(JointIndex joint) const { return joint_names_.at(joint.value()); }
  const std::string& actuatorName(ActuatorIndex actuator) const {
    return actuator_names_.at(actuator.value());
  }
  bool hasJoint(const std::string& name) const { return joint_index_.count(name) != 0; }
  bool hasActuator(const std::string& name) const { return actuator_index_.count(name) != 0; }
  // Throws servoloop::ConfigError naming the joint and listing the known ones.
  JointIndex jointIndex(const std::string& name) const;
  // Throws servoloop::ConfigError naming the actuator and listing the known ones.
  ActuatorIndex actuatorIndex(const std::string& name) const;

  // Real-time safe direct access for backends (indices are not range-checked
  // beyond a debug assert).
  JointValues& joint(JointIndex joint) noexcept {
    assert(joint.value() < joints_.size());
    return joints_[joint.value()];
  }
  const JointValues& joint(JointIndex joint) const noexcept {
    assert(joint.value() < joints_.size());
    return joints_[joint.value()];
  }
  ActuatorValues& actuator(ActuatorIndex actuator) noexcept {
    assert(actuator.value() < actuators_.size());
    return actuators_[actuator.value()];
  }
  const ActuatorValues& actuator(ActuatorIndex actuator) const noexcept {
    assert(actuator.value() < actuators_.size());
    return actuators_[actuator.value()];
  }

  const JointCommandInterfaces& jointCommandInterfaces(JointIndex joint) const {
    return joint_commands_.at(joint.value());
  }
  // Joints that received an implicit SimpleTransmission, by name.
  const std::vector<std::string>& implicitTransmissionJoints() const noexcept {
    return implicit_joints_;
  }

 private:
  // One transmission with its pointer tables into the storage below, built
  // once so the real-time maps only dereference.
  struct Binding {
    std::string name;
    std::unique_ptr<Transmission> transmission;
    ActuatorData actuator_state;
    ActuatorData actuator_command;  // position/velocity/effort → the *_command fields
    JointData joint_state;
    JointData joint_command;
    JointCommandInterfaces commands;  // union over the transmission's joints
  };

  // A SimpleTransmission's binding, flattened: indices into joints_ and
  // actuators_, its reduction and offset.
  struct SimpleBinding {
    std::size_t joint = 0;
    std::size_t actuator = 0;
    double reduction = 1.0;
    double joint_offset = 0.0;
    JointCommandInterfaces commands;
  };

  // The maps of the transmissions other than SimpleTransmissions.
  void generalJointCommandToActuatorCommand() noexcept;
  void generalJointStateToActuatorState() noexcept;

  void addTransmission(const TransmissionInfo& info, const urdf::ModelInterface& robot,
                       const Options& options);
  void bindStorage();
  void fillInterfaces();

  std::vector<JointValues> joints_;
  std::vector<ActuatorValues> actuators_;
  std::vector<std::string> joint_names_;
  std::vector<std::string> actuator_names_;
  std::vector<JointCommandInterfaces> joint_commands_;
  std::unordered_map<std::string, std::size_t> joint_index_;
  std::unordered_map<std::string, std::size_t> actuator_index_;
  std::vector<std::string> implicit_joints_;
  std::vector<Binding> bindings_;
  std::vector<SimpleBinding> simple_bindings_;  // the SimpleTransmissions among bindings_
  std::vector<Binding*> general_bindings_;       // all the others
  // Per binding, the joint and actuator indices it covers (in its order).
  std::vector<std::vector<std::size_t>> binding_joints_;
  std::vector<std::vector<std::size_t>> binding_actuators_;

  hardware_interface::JointStateInterface joint_state_interface_;
  hardware_interface::EffortJointInterface effort_joint_interface_;
  hardware_interface::VelocityJointInterface velocity_joint_interface_;
  hardware_interface::PositionJointInterface position_joint_interface_;
  hardware_interface::ActuatorStateInterface actuator_state_interface_;
  hardware_interface::EffortActuatorInterface effort_actuator_interface_;
  hardware_interface::VelocityActuatorInterface velocity_actuator_interface_;
  hardware_interface::PositionActuatorInterface position_actuator_interface_;
};

}  // namespace servoloop::transmissions
