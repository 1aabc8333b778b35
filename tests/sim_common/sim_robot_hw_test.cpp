// SimRobotHW's shared logic against a recording engine: which interfaces the
// seed robots get, what reaches the engine after limits, motor limits,
// command modes and the emergency stop. Expected values are hand calculations
// from the rules in the reference doc (joint limits, transmissions).
#include <cmath>
#include <limits>
#include <memory>

#include <gtest/gtest.h>

#include "fake_engine.hpp"
#include "servoloop/hardware_interface/actuator_interfaces.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/sim_common/sim_robot_hw.hpp"
#include "sim_test_support.hpp"

namespace servoloop::sim_common {
namespace {

namespace hi = hardware_interface;
using sim_testing::armUrdf;
using sim_testing::controllerClaiming;
using sim_testing::FakeEngine;
using sim_testing::makeInfo;

constexpr Duration kPeriod(0.001);
constexpr JointIndex kJoint0(0);

struct Rig {
  FakeEngine* engine = nullptr;
  std::unique_ptr<SimRobotHW> hw;

  // One control cycle as the loop runs it; `command` is written between read and write.
  AppliedJointCommand cycle(hi::JointHandle& handle, double command) {
    hw->read(Time(), kPeriod);
    handle.setCommand(command);
    hw->write(Time(), kPeriod);
    hw->step();
    return hw->appliedCommand(kJoint0);
  }
};

Rig makeRig(const hi::HardwareInfo& info) {
  auto engine = std::make_unique<FakeEngine>();
  Rig rig;
  rig.engine = engine.get();
  rig.hw = std::make_unique<SimRobotHW>(std::move(engine));
  rig.hw->init(info);
  return rig;
}

Rig seedRig(bool with_joint_control, const std::string& yaml = "") {
  const std::string path = sim_testing::seedUrdfPath(with_joint_control);
  return makeRig(makeInfo(sim_testing::readFile(path), yaml, path));
}

std::vector<std::string> names(const hi::HardwareInterface* iface) {
  return iface == nullptr ? std::vector<std::string>{} : iface->getNames();
}

TEST(SimRobotHW, SeedRobotWithTransmissionOffersJoint1ThroughTran1AndMotor1) {
  // Loaded from the file path alone, as a launch file gives it.
  hi::HardwareInfo info = makeInfo("", "", sim_testing::seedUrdfPath(true));
  Rig rig = makeRig(info);
  SimRobotHW& hw = *rig.hw;

  EXPECT_EQ(names(hw.get<hi::JointStateInterface>()), std::vector<std::string>{"joint1"});
  EXPECT_EQ(names(hw.get<hi::EffortJointInterface>()), std::vector<std::string>{"joint1"});
  EXPECT_EQ(hw.get<hi::VelocityJointInterface>(), nullptr);
  EXPECT_EQ(hw.get<hi::PositionJointInterface>(), nullptr);
  EXPECT_EQ(names(hw.get<hi::ActuatorStateInterface>()), std::vector<std::string>{"motor1"});
  EXPECT_EQ(names(hw.get<hi::EffortActuatorInterface>()), std::vector<std::string>{"motor1"});
  EXPECT_TRUE(hw.transmissions().implicitTransmissionJoints().empty());
  EXPECT_EQ(hw.transmissions().numTransmissions(), 1u);
  EXPECT_EQ(hw.limitEnforcement(kJoint0, JointCommandMode::effort), LimitEnforcement::saturation);
  EXPECT_EQ(rig.engine->configs.at(0).name, "joint1");
  EXPECT_DOUBLE_EQ(rig.engine->configs.at(0).motor_effort_limit, 10.0);
}

TEST(SimRobotHW, SeedRobotWithoutTransmissionGetsAnImplicitOne) {
  Rig rig = seedRig(false);
  SimRobotHW& hw = *rig.hw;
  EXPECT_EQ(hw.transmissions().implicitTransmissionJoints(), std::vector<std::string>{"joint1"});
  EXPECT_EQ(names(hw.get<hi::EffortJointInterface>()), std::vector<std::string>{"joint1"});
  EXPECT_EQ(names(hw.get<hi::ActuatorStateInterface>()), std::vector<std::string>{"joint1_motor"});
  // A continuous joint without <limit>: nothing to enforce, no motor bound.
  EXPECT_EQ(hw.limitEnforcement(kJoint0, JointCommandMode::effort), LimitEnforcement::none);
  EXPECT_TRUE(std::isinf(rig.engine->configs.at(0).motor_effort_limit));
}

TEST(SimRobotHW, EffortCommandIsSaturatedBeforeItReachesTheEngine) {
  Rig rig = seedRig(true);
  rig.hw->doSwitch({controllerClaiming("c", "EffortJointInterface", {"joint1"})}, {});
  hi::JointHandle handle = rig.hw->get<hi::EffortJointInterface>()->getHandle("joint1");

  EXPECT_DOUBLE_EQ(rig.cycle(handle, 50.0).value, 10.0);
  EXPECT_EQ(rig.engine->state[0].last_mode, JointCommandMode::effort);
  EXPECT_DOUBLE_EQ(rig.engine->state[0].last_command, 10.0);
  EXPECT_DOUBLE_EQ(rig.cycle(handle, -50.0).value, -10.0);
  EXPECT_DOUBLE_EQ(rig.engine->state[0].last_command, -10.0);
  EXPECT_DOUBLE_EQ(rig.cycle(handle, 4.0).value, 4.0);
}

TEST(SimRobotHW, SaturationStopsPushingFurtherPastThePositionLimit) {
  Rig rig = seedRig(true);
  rig.hw->setJointCommandMode(kJoint0, JointCommandMode::effort);
  hi::JointHandle handle = rig.hw->get<hi::EffortJointInterface>()->getHandle("joint1");
  rig.engine->state[0].position = 2.5;  // above the upper limit 2: upper bound becomes 0
  EXPECT_DOUBLE_EQ(rig.cycle(handle, 5.0).value, 0.0);
  EXPECT_DOUBLE_EQ(rig.cycle(handle, -3.0).value, -3.0);
  rig.engine->state[0].position = 1.0;
  rig.engine->state[0].velocity = -0.6;  // faster than 0.5 rad/s downwards: lower bound 0
  EXPECT_DOUBLE_EQ(rig.cycle(handle, -3.0).value, 0.0);
  EXPECT_DOUBLE_EQ(rig.cycle(handle, 3.0).value, 3.0);
}

TEST(SimRobotHW, EffortSoftLimitsFromTheUrdfSafetyController) {
  const std::string limits =
      R"(<limit lower="-1" upper="1" effort="10" velocity="1"/>
         <safety_controller soft_lower_limit="-0.5" soft_upper_limit="0.5" k_position="10" k_velocity="2"/>)";
  Rig rig = makeRig(makeInfo(armUrdf(1.0, sim_testing::kEffortInterface, "revolute", limits)));
  EXPECT_EQ(rig.hw->limitEnforcement(kJoint0, JointCommandMode::effort), LimitEnforcement::soft_limits);
  rig.hw->setJointCommandMode(kJoint0, JointCommandMode::effort);
  hi::JointHandle handle = rig.hw->get<hi::EffortJointInterface>()->getHandle("arm_joint");

  // p = 0, v = 0: v_lo = clamp(-10·0.5, ±1) = -1, v_hi = clamp(10·0.5, ±1) = 1,
  // e_lo = clamp(-2·(0 + 1), ±10) = -2, e_hi = clamp(-2·(0 - 1), ±10) = 2.
  EXPECT_DOUBLE_EQ(rig.cycle(handle, 5.0).value, 2.0);
  // p = 0.6: v_lo = clamp(-11, ±1) = -1, v_hi = clamp(-1, ±1) = -1, so e_lo = e_hi = -2.
  rig.engine->state[0].position = 0.6;
  EXPECT_DOUBLE_EQ(rig.cycle(handle, 5.0).value, -2.0);
}

TEST(SimRobotHW, EffortSoftLimitsFromTheYamlOverrideTheUrdf) {
  const std::string yaml = R"(
joint_limits:
  joint1: {has_soft_limits: true, k_position: 10, k_velocity: 2, soft_lower_limit: 0.5, soft_upper_limit: 1.5}
)";
  Rig rig = seedRig(true, yaml);
  EXPECT_EQ(rig.hw->limitEnforcement(kJoint0, JointCommandMode::effort), LimitEnforcement::soft_limits);
  rig.hw->setJointCommandMode(kJoint0, JointCommandMode::effort);
  hi::JointHandle handle = rig.hw->get<hi::EffortJointInterface>()->getHandle("joint1");
  // p = 0 below the soft band, v = 0 (v_max 0.5, e_max 10): v_lo = clamp(5, ±0.5) = 0.5,
  // v_hi = clamp(15, ±0.5) = 0.5, e_lo = e_hi = clamp(-2·(0 - 0.5), ±10) = 1.
  EXPECT_DOUBLE_EQ(rig.cycle(handle, -5.0).value, 1.0);
}

TEST(SimRobotHW, ControllerSwitchSetsModesAndAStoppedControllersJointGetsZeroEffort) {
  Rig rig = seedRig(true);
  hi::JointHandle handle = rig.hw->get<hi::EffortJointInterface>()->getHandle("joint1");
  // No controller yet: mode none, zero effort whatever the command storage holds.
  EXPECT_EQ(rig.hw->jointCommandMode(kJoint0), JointCommandMode::none);
  EXPECT_DOUBLE_EQ(rig.cycle(handle, 3.0).value, 0.0);
  EXPECT_EQ(rig.engine->state[0].last_mode, JointCommandMode::effort);
  EXPECT_DOUBLE_EQ(rig.engine->state[0].last_command, 0.0);

  const auto controller = controllerClaiming("joint1_position_controller", "EffortJointInterface", {"joint1"});
  rig.hw->doSwitch({controller}, {});
  EXPECT_EQ(rig.hw->jointCommandMode(kJoint0), JointCommandMode::effort);
  EXPECT_DOUBLE_EQ(rig.cycle(handle, 3.0).value, 3.0);
  EXPECT_DOUBLE_EQ(rig.engine->state[0].last_command, 3.0);

  rig.hw->doSwitch({}, {controller});
  EXPECT_EQ(rig.hw->jointCommandMode(kJoint0), JointCommandMode::none);
  const AppliedJointCommand applied = rig.cycle(handle, 3.0);
  EXPECT_EQ(applied.mode, JointCommandMode::none);
  EXPECT_DOUBLE_EQ(applied.value, 0.0);
  EXPECT_DOUBLE_EQ(rig.engine->state[0].last_command, 0.0);
}

TEST(SimRobotHW, SwitchPicksTheModeOfTheClaimedInterfaceStopsFirst) {
  Rig rig = makeRig(makeInfo(armUrdf(1.0, sim_testing::kAllJointInterfaces)));
  const auto position = controllerClaiming("p", "PositionJointInterface", {"arm_joint"});
  const auto velocity = controllerClaiming("v", "hardware_interface::VelocityJointInterface", {"arm_joint"});
  rig.hw->doSwitch({position}, {});
  EXPECT_EQ(rig.hw->jointCommandMode(kJoint0), JointCommandMode::position);
  rig.hw->doSwitch({velocity}, {position});
  EXPECT_EQ(rig.hw->jointCommandMode(kJoint0), JointCommandMode::velocity);
  hi::JointHandle handle = rig.hw->get<hi::VelocityJointInterface>()->getHandle("arm_joint");
  EXPECT_DOUBLE_EQ(rig.cycle(handle, 0.25).value, 0.25);
  EXPECT_EQ(rig.engine->state[0].last_mode, JointCommandMode::velocity);
}

TEST(SimRobotHW, PrepareSwitchRefusesClaimsTheSimulationCannotHonour) {
  Rig rig = seedRig(true);
  EXPECT_TRUE(rig.hw->prepareSwitch({controllerClaiming("ok", "EffortJointInterface", {"joint1"})}, {}));
  EXPECT_FALSE(rig.hw->prepareSwitch({controllerClaiming("a", "EffortActuatorInterface", {"motor1"})}, {}));
  EXPECT_FALSE(rig.hw->prepareSwitch({controllerClaiming("v", "VelocityJointInterface", {"joint1"})}, {}));
  EXPECT_FALSE(rig.hw->prepareSwitch({controllerClaiming("x", "EffortJointInterface", {"joint9"})}, {}));
}

TEST(SimRobotHW, EmergencyStopFreezesPositionsAndZeroesEffortAndVelocity) {
  Rig rig = makeRig(makeInfo(armUrdf(1.0, sim_testing::kAllJointInterfaces)));
  SimRobotHW& hw = *rig.hw;
  hi::JointHandle position = hw.get<hi::PositionJointInterface>()->getHandle("arm_joint");
  hi::JointHandle velocity = hw.get<hi::VelocityJointInterface>()->getHandle("arm_joint");
  hi::JointHandle effort = hw.get<hi::EffortJointInterface>()->getHandle("arm_joint");
  hw.setJointCommandMode(kJoint0, JointCommandMode::position);
  rig.engine->state[0].position = 0.3;
  EXPECT_DOUBLE_EQ(rig.cycle(position, 1.0).value, 1.0);

  hw.setEmergencyStop(true);
  EXPECT_DOUBLE_EQ(rig.cycle(position, 1.0).value, 0.3);  // the position measured when engaged
  EXPECT_TRUE(hw.emergencyStopActive());
  rig.engine->state[0].position = 0.4;  // drifting does not move the frozen target
  EXPECT_DOUBLE_EQ(rig.cycle(position, 1.5).value, 0.3);
  EXPECT_EQ(rig.engine->state[0].last_mode, JointCommandMode::position);
  EXPECT_DOUBLE_EQ(rig.engine->state[0].last_command, 0.3);

  hw.setJointCommandMode(kJoint0, JointCommandMode::velocity);
  EXPECT_DOUBLE_EQ(rig.cycle(velocity, 2.0).value, 0.0);
  hw.setJointCommandMode(kJoint0, JointCommandMode::effort);
  EXPECT_DOUBLE_EQ(rig.cycle(effort, 7.0).value, 0.0);

  hw.setEmergencyStop(false);
  EXPECT_DOUBLE_EQ(rig.cycle(effort, 7.0).value, 7.0);
  EXPECT_FALSE(hw.emergencyStopActive());
  hw.setJointCommandMode(kJoint0, JointCommandMode::position);
  EXPECT_DOUBLE_EQ(rig.cycle(position, 1.5).value, 1.5);
}

TEST(SimRobotHW, MotorEffortLimitActsInActuatorSpaceAfterTheReduction) {
  const std::string yaml = "actuators: {arm_motor: {max_effort: 0.2, rotor_inertia: 1.0e-4}}";
  Rig rig = makeRig(makeInfo(armUrdf(50.0, sim_testing::kEffortInterface), yaml));
  SimRobotHW& hw = *rig.hw;
  hw.setJointCommandMode(kJoint0, JointCommandMode::effort);
  hi::JointHandle handle = hw.get<hi::EffortJointInterface>()->getHandle("arm_joint");
  const transmissions::ActuatorValues& motor = hw.transmissions().actuator(ActuatorIndex(0));

  // 100 N·m at the joint asks 2 N·m of the motor; it gives 0.2, i.e. 10 N·m at the joint.
  EXPECT_DOUBLE_EQ(rig.cycle(handle, 100.0).value, 10.0);
  EXPECT_DOUBLE_EQ(motor.effort_command, 0.2);
  EXPECT_DOUBLE_EQ(rig.cycle(handle, -100.0).value, -10.0);
  EXPECT_DOUBLE_EQ(motor.effort_command, -0.2);
  // Within the motor's range the command passes unchanged (4 N·m ← 0.08 N·m).
  EXPECT_NEAR(rig.cycle(handle, 4.0).value, 4.0, 1e-12);
  EXPECT_NEAR(motor.effort_command, 0.08, 1e-15);

  // What the engine is told about the joint: 50 · 0.2 N·m, and 50² · 1e-4 kg·m².
  EXPECT_DOUBLE_EQ(hw.engineJointConfig(kJoint0).motor_effort_limit, 10.0);
  EXPECT_DOUBLE_EQ(hw.engineJointConfig(kJoint0).reflected_rotor_inertia, 0.25);
}

TEST(SimRobotHW, JointEffortLimitTighterThanTheMotorBoundsTheEngineMotor) {
  const std::string yaml = "actuators: {arm_motor: {max_effort: 0.2}}";
  Rig rig = makeRig(makeInfo(
      armUrdf(50.0, sim_testing::kEffortInterface, "continuous", R"(<limit effort="8" velocity="3"/>)"), yaml));
  EXPECT_DOUBLE_EQ(rig.hw->engineJointConfig(kJoint0).motor_effort_limit, 8.0);
}

TEST(SimRobotHW, ReadShowsTheEngineStateInJointAndActuatorSpace) {
  Rig rig = makeRig(makeInfo(armUrdf(50.0, sim_testing::kEffortInterface, "continuous", "", 1.0, 0.1)));
  SimRobotHW& hw = *rig.hw;
  rig.engine->state[0] = {0.3, 0.2, 10.0};
  hw.read(Time(), kPeriod);
  const hi::JointStateHandle joint = hw.get<hi::JointStateInterface>()->getHandle("arm_joint");
  EXPECT_NEAR(joint.getPosition(), 0.3, 1e-12);
  EXPECT_NEAR(joint.getVelocity(), 0.2, 1e-12);
  EXPECT_NEAR(joint.getEffort(), 10.0, 1e-12);
  // Actuator = motor side of the 50:1 gear with joint offset 0.1:
  // position 50·(0.3 − 0.1), velocity 50·0.2, effort 10 / 50.
  const hi::ActuatorStateHandle motor = hw.get<hi::ActuatorStateInterface>()->getHandle("arm_motor");
  EXPECT_NEAR(motor.getPosition(), 10.0, 1e-12);
  EXPECT_NEAR(motor.getVelocity(), 10.0, 1e-12);
  EXPECT_NEAR(motor.getEffort(), 0.2, 1e-12);
}

TEST(SimRobotHW, WorldSettingsReachTheEngineAndDriveSimulatedTime) {
  const std::string yaml = R"(
sim:
  time_step: 0.002
  gravity: [0, 0, -1.62]
  ground_plane: true
  initial_positions: {arm_joint: 0.4}
)";
  Rig rig = makeRig(makeInfo(armUrdf(1.0, sim_testing::kEffortInterface), yaml));
  SimRobotHW& hw = *rig.hw;
  EXPECT_DOUBLE_EQ(rig.engine->settings_seen.time_step_s, 0.002);
  EXPECT_DOUBLE_EQ(rig.engine->settings_seen.gravity.z(), -1.62);
  EXPECT_TRUE(rig.engine->settings_seen.ground_plane);
  EXPECT_DOUBLE_EQ(rig.engine->configs.at(0).initial_position, 0.4);
  EXPECT_DOUBLE_EQ(hw.timeStep().seconds, 0.002);

  hw.setJointCommandMode(kJoint0, JointCommandMode::effort);
  hi::JointHandle handle = hw.get<hi::EffortJointInterface>()->getHandle("arm_joint");
  for (int k = 0; k < 3; ++k) rig.cycle(handle, 1.0);
  EXPECT_DOUBLE_EQ(hw.simTime().seconds, 0.006);
  EXPECT_EQ(rig.engine->steps, 3);

  rig.engine->state[0].position = 1.7;
  hw.reset();
  EXPECT_DOUBLE_EQ(hw.simTime().seconds, 0.0);
  EXPECT_DOUBLE_EQ(handle.getCommand(), 0.0);
  EXPECT_DOUBLE_EQ(handle.getPosition(), 0.4);
  EXPECT_DOUBLE_EQ(hw.appliedCommand(kJoint0).value, 0.0);
}

TEST(SimRobotHW, NonFiniteCommandsWithoutLimitsBecomeHarmless) {
  Rig rig = makeRig(makeInfo(armUrdf(1.0, sim_testing::kAllJointInterfaces)));
  SimRobotHW& hw = *rig.hw;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  hw.setJointCommandMode(kJoint0, JointCommandMode::effort);
  hi::JointHandle effort = hw.get<hi::EffortJointInterface>()->getHandle("arm_joint");
  EXPECT_DOUBLE_EQ(rig.cycle(effort, nan).value, 0.0);
  hw.setJointCommandMode(kJoint0, JointCommandMode::position);
  hi::JointHandle position = hw.get<hi::PositionJointInterface>()->getHandle("arm_joint");
  rig.engine->state[0].position = 0.7;
  EXPECT_DOUBLE_EQ(rig.cycle(position, nan).value, 0.7);  // holds where it is
}

}  // namespace
}  // namespace servoloop::sim_common
