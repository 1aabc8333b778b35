#pragma once
// SimRobotHW: everything simulation backends share. A backend is a
// PhysicsEngine handed to this class; this class turns it into a RobotHW that
// controllers cannot tell from real hardware ("hardware is actuators"):
//
//   read():  engine joint state ─▶ joint state (what controllers see) and,
//            through jointStateToActuatorState, the actuator state (what the
//            motors measure)
//   write(): joint limits on the active command interfaces ─▶ emergency stop
//            ─▶ jointCommandToActuatorCommand ─▶ motor limits (actuators/<name>/
//            max_effort) ─▶ actuatorCommandToJointCommand ─▶ applied commands
//            (read() also samples the URDF's IMUs and force-torque sensors,
//            simulated_sensors.hpp, offered as ImuSensorInterface and
//            ForceTorqueSensorInterface)
//   step():  applied commands ─▶ engine, one physics step
//
// Every transmission map is linear and invertible, so the round trips
// joint → actuator → joint give back the same values (up to rounding); they
// are taken only where something happens in actuator space: the motor effort
// limits. Without any max_effort, write() maps the joint commands to the
// actuators (for actuator-space readers) and applies the joint commands as
// they are; read() never maps back.
//
// Joints without a <transmission> get an implicit SimpleTransmission
// (reduction 1, EffortJointInterface, actuator "<joint>_motor").
//
// Threading: init(), prepareSwitch(), checkForConflict() and reset() are
// non-real-time. read(), write(), step(), doSwitch() and setEmergencyStop()
// run on the real-time thread: no allocation, no locks, no logging, no
// exceptions. The inspection getters are for tests and tools (not real-time
// unless marked).
#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <urdf_model/model.h>

#include "servoloop/hardware_interface/joint_limits_loader.hpp"
#include "servoloop/hardware_interface/simulated_robot_hw.hpp"
#include "servoloop/core/strong_index.hpp"
#include "servoloop/sim_common/joint_command_limiter.hpp"
#include "servoloop/sim_common/physics_engine.hpp"
#include "servoloop/sim_common/sim_settings.hpp"
#include "servoloop/sim_common/simulated_sensors.hpp"
#include "servoloop/transmissions/robot_transmissions.hpp"

namespace servoloop::sim_common {

class SimRobotHW : public hardware_interface::SimulatedRobotHW {
 public:
  // `engine` must not be null; SimRobotHW owns it.
  explicit SimRobotHW(std::unique_ptr<PhysicsEngine> engine);
  ~SimRobotHW() override;
  SimRobotHW(const SimRobotHW&) = delete;
  SimRobotHW& operator=(const SimRobotHW&) = delete;

  // Non-real-time. Parses and validates the URDF (info.urdf_xml, or the file
  // info.urdf_path when the text is empty), builds the transmissions (implicit
  // ones for joints without), loads the joint limits (URDF + <ns>/joint_limits),
  // the world settings (<ns>/sim) and motor parameters (<ns>/actuators), builds
  // the engine's world and registers the joint and actuator interfaces.
  // Throws servoloop::ConfigError naming the file or key at fault. Call once.
  void init(const hardware_interface::HardwareInfo& info) override;
  // Non-real-time, before init(): the engine builds the robot into `world`.
  void joinWorld(hardware_interface::SimulatedWorld& world) override { engine_->joinWorld(world); }

  // Real-time. Joint and actuator state from the engine (time and period are
  // not used: the state is the engine's after the last step()).
  ReturnType read(Time time, Duration period) override;
  // Real-time. Computes the applied commands from the controllers' joint
  // commands; `period` drives the rate-dependent limits.
  ReturnType write(Time time, Duration period) override;

  // Non-real-time. Refuses (false, logged) a controller that claims an
  // actuator command interface or a joint this hardware does not have:
  // in simulation, controllers command joints.
  bool prepareSwitch(const std::vector<hardware_interface::ControllerInfo>& start_list,
                     const std::vector<hardware_interface::ControllerInfo>& stop_list) override;
  // Real-time. The joints of stopped controllers go to mode none (zero
  // effort), then those of started controllers to the mode of the joint
  // interface they claim (EffortJointInterface → effort, ...). Always ok:
  // prepareSwitch refused what the simulation cannot do.
  ReturnType doSwitch(const std::vector<hardware_interface::ControllerInfo>& start_list,
                      const std::vector<hardware_interface::ControllerInfo>& stop_list) override;

  Duration timeStep() const override;
  // Real-time. Hands the applied commands to the engine and steps it once.
  ReturnType step() override;
  Time simTime() const override;
  // Non-real-time. Engine back to its initial state, every command (joint and
  // actuator) zeroed, limit handles reset, sim time 0. Command modes and the
  // emergency stop stay as they are.
  void reset() override;
  // Real-time safe, from any thread; takes effect at the next write().
  void setEmergencyStop(bool engaged) override;
  // Non-real-time, no cycle running: the engine's joints teleported, at rest.
  void setJointPositions(const std::vector<std::string>& joints, const std::vector<double>& positions) override;

  // Real-time safe. Sets a joint's command mode directly, as doSwitch does
  // (for a loop without a controller manager, and for tests).
  void setJointCommandMode(JointIndex joint, JointCommandMode mode) noexcept;

  // --- inspection ---------------------------------------------------------
  std::size_t numJoints() const noexcept { return applied_.size(); }
  // Joints are numbered as RobotTransmissions numbers them.
  transmissions::RobotTransmissions& transmissions() { return *transmissions_; }
  const transmissions::RobotTransmissions& transmissions() const { return *transmissions_; }
  const urdf::ModelInterface& model() const { return *model_; }

  bool readBaseGroundTruth(hardware_interface::BaseGroundTruth& out) const noexcept override;
  // Non-real-time, no cycle running: the engine's floating base teleported.
  void setBaseState(const hardware_interface::BaseGroundTruth& state) override;
  const SimSettings& settings() const noexcept { return settings_; }
  const hardware_interface::RobotJointLimits& jointLimits() const noexcept { return joint_limits_; }
  const ActuatorParameters& actuatorParameters(ActuatorIndex actuator) const {
    return actuator_parameters_.at(actuator.value());
  }
  const EngineJointConfig& engineJointConfig(JointIndex joint) const {
    return engine_joints_.at(joint.value());
  }
  const PhysicsEngine& engine() const noexcept { return *engine_; }
  const std::vector<SensorDescription>& sensorDescriptions() const noexcept { return sensor_descriptions_; }
  // Real-time safe getters.
  JointCommandMode jointCommandMode(JointIndex joint) const noexcept;
  AppliedJointCommand appliedCommand(JointIndex joint) const noexcept;
  bool emergencyStopActive() const noexcept { return estop_active_; }
  LimitEnforcement limitEnforcement(JointIndex joint, JointCommandMode mode) const noexcept;

 private:
  void warnAboutLimits(const EngineJointConfig& joint, const hardware_interface::JointLimits& limits) const;
  void checkBase(const std::string& ns) const;
  void loadModel(const hardware_interface::HardwareInfo& info);
  void configureActuators(const std::string& ns, const YAML::Node& parameters);
  void configureEngineJoints();
  void initSensors();
  void readEngineState() noexcept;
  // write()'s rare paths, out of line.
  [[gnu::noinline]] void changeEmergencyStop(bool engaged) noexcept;
  [[gnu::noinline]] void limitMotorEfforts() noexcept;
  [[gnu::noinline]] void applyEmergencyStop() noexcept;
  void zeroCommands() noexcept;
  void applyModesFromClaims(const hardware_interface::ControllerInfo& controller,
                            bool starting) noexcept;

  std::unique_ptr<PhysicsEngine> engine_;
  std::string source_name_;
  std::shared_ptr<const urdf::ModelInterface> model_;
  bool urdf_self_collide_ = false;  // <gazebo><self_collide> of the description
  std::map<std::string, double> urdf_link_friction_;  // <gazebo reference><mu1>/<mu2>, by link
  std::unique_ptr<transmissions::RobotTransmissions> transmissions_;
  std::vector<SensorDescription> sensor_descriptions_;  // the URDF's <gazebo> sensors
  SimulatedSensors sensors_;
  hardware_interface::RobotJointLimits joint_limits_;
  SimSettings settings_;

  // Per joint (RobotTransmissions' joint order).
  std::vector<EngineJointConfig> engine_joints_;
  std::vector<JointCommandLimiter> limiters_;
  std::vector<JointCommandMode> modes_;
  std::vector<AppliedJointCommand> applied_;
  std::vector<double> estop_positions_;  // measured when the stop was engaged
  std::vector<EngineJointState> engine_states_;  // read() buffer

  // Per actuator (RobotTransmissions' actuator order).
  std::vector<ActuatorParameters> actuator_parameters_;

  bool any_motor_limit_ = false;  // some actuator has a finite max_effort

  std::atomic<bool> estop_requested_{false};
  bool estop_active_ = false;
  std::uint64_t steps_ = 0;
};

}  // namespace servoloop::sim_common
