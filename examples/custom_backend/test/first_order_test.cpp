// Loads the "first_order" backend the way `servoloop launch` does — through
// the plugin loader, by its type name, as a RobotHW that is also a
// SimulatedRobotHW — initialises it from a URDF and parameters, and runs
// control cycles (read → command → write → step) by hand. Expected states come
// from the analytic solution of the model (τ·dv/dt = v* − v, dq/dt = v from
// rest):
//
//   v(t) = v*·(1 − e^(−t/τ)),   q(t) = q0 + v*·(t − τ·(1 − e^(−t/τ)))
//
// worked out in the comments, not from the backend's own update formula.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "servoloop/plugin/plugin_loader.hpp"
#include "servoloop/hardware_interface/actuator_interfaces.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/hardware_interface/robot_hw.hpp"
#include "servoloop/hardware_interface/simulated_robot_hw.hpp"

namespace {

namespace hi = servoloop::hardware_interface;
using servoloop::Duration;
using servoloop::ReturnType;
using servoloop::Time;

constexpr const char* kType = "first_order";

// config/wheel.urdf: one continuous joint "wheel" (velocity limit 1 rad/s,
// effort limit 10 N·m) behind a 10:1 SimpleTransmission offering velocity and
// position commands, actuator "wheel_motor".
const std::string kWheelUrdf = std::string(MY_BACKENDS_CONFIG_DIR) + "/wheel.urdf";

// What the controller manager tells the hardware when a controller claiming
// `joint` through `interface` starts.
hi::ControllerInfo claiming(const std::string& interface, const std::string& joint) {
  return hi::ControllerInfo{"test_controller", "test/Type", {hi::InterfaceResources{interface, {joint}}}};
}

class FirstOrderBackendTest : public ::testing::Test {
 protected:
  // The build folder first; SERVOLOOP_PLUGIN_PATH and the installed plugin
  // folder follow, as in a running node.
  FirstOrderBackendTest() : loader_(servoloop::plugin::pluginSearchPath({MY_BACKENDS_PLUGIN_BUILD_DIR})) {}

  // Creates the backend by type name and initialises it as a node would.
  void create(const std::string& urdf_xml, const std::string& urdf_path, const std::string& ns,
              const std::string& params_yaml) {
    hw_ = loader_.create<hi::RobotHW>(kType);
    sim_ = dynamic_cast<hi::SimulatedRobotHW*>(hw_.get());
    ASSERT_NE(sim_, nullptr) << "first_order is not a SimulatedRobotHW";
    hi::HardwareInfo info;
    info.urdf_xml = urdf_xml;
    info.urdf_path = urdf_path;
    info.robot_namespace = ns;
    info.parameters = YAML::Load(params_yaml);
    hw_->init(info);
  }

  void startController(const std::string& interface, const std::string& joint) {
    const std::vector<hi::ControllerInfo> start{claiming(interface, joint)};
    ASSERT_TRUE(hw_->prepareSwitch(start, {}));
    hw_->doSwitch(start, {});
  }

  // One SimulationLoop cycle, with `command` written by "the controller".
  void cycle(hi::JointHandle& joint, double command) {
    const Duration dt = sim_->timeStep();
    ASSERT_EQ(hw_->read(sim_->simTime(), dt), ReturnType::ok);
    joint.setCommand(command);
    ASSERT_EQ(hw_->write(sim_->simTime(), dt), ReturnType::ok);
    ASSERT_EQ(sim_->step(), ReturnType::ok);
  }

  // The state a controller sees after the last step.
  hi::JointStateHandle state(const std::string& joint) {
    EXPECT_EQ(hw_->read(sim_->simTime(), sim_->timeStep()), ReturnType::ok);
    return hw_->get<hi::JointStateInterface>()->getHandle(joint);
  }

  servoloop::plugin::PluginLoader loader_;
  servoloop::plugin::PluginPtr<hi::RobotHW> hw_;
  hi::SimulatedRobotHW* sim_ = nullptr;
};

// --- the seed robot: one continuous joint, no <transmission> -------------------------------

const std::string kSeedParams = "{sim: {time_step: 0.01}, first_order: {time_constant: 0.1, damping: 2.0}}";

TEST_F(FirstOrderBackendTest, ThePluginLoaderListsItAsARobotHwFromTheBuildFolder) {
  const std::vector<servoloop::plugin::PluginTypeInfo> backends = loader_.listTypes("robot_hw");
  const auto it = std::find_if(backends.begin(), backends.end(),
                               [](const servoloop::plugin::PluginTypeInfo& info) { return info.type == kType; });
  ASSERT_NE(it, backends.end()) << kType << " is not listed as a robot_hw type";
  EXPECT_EQ(std::filesystem::canonical(it->library).parent_path(),
            std::filesystem::canonical(MY_BACKENDS_PLUGIN_BUILD_DIR));
}

TEST_F(FirstOrderBackendTest, SeedRobotUnderAnEffortCommandFollowsTheAnalyticSolution) {
  ASSERT_NO_FATAL_FAILURE(create("", MY_BACKENDS_SEED_URDF, "/one_DOF_robot", kSeedParams));
  EXPECT_DOUBLE_EQ(sim_->timeStep().seconds, 0.01);
  // joint1 has no <transmission>: SimRobotHW gave it an implicit one (effort, joint1_motor).
  ASSERT_NO_FATAL_FAILURE(startController("EffortJointInterface", "joint1"));
  hi::JointHandle joint1 = hw_->get<hi::EffortJointInterface>()->getHandle("joint1");

  // 1 N·m against damping 2 N·m·s/rad: v* = 0.5 rad/s, τ = 0.1 s.
  for (int n = 0; n < 3; ++n) ASSERT_NO_FATAL_FAILURE(cycle(joint1, 1.0));
  EXPECT_NEAR(sim_->simTime().seconds, 0.03, 1e-12);
  const hi::JointStateHandle after = state("joint1");
  // v(0.03) = 0.5·(1 − e^(−0.3)) = 0.5·(1 − 0.7408182207) = 0.1295908897 rad/s
  EXPECT_NEAR(after.getVelocity(), 0.1295908897, 1e-9);
  // q(0.03) = 0.5·(0.03 − 0.1·(1 − e^(−0.3))) = 0.5·(0.03 − 0.0259181779) = 0.0020409110 rad
  EXPECT_NEAR(after.getPosition(), 0.0020409110, 1e-9);
  EXPECT_DOUBLE_EQ(after.getEffort(), 1.0);  // effort mode reports the applied effort
  // The actuator side of the implicit reduction-1 transmission reads the same.
  const hi::ActuatorStateHandle motor = hw_->get<hi::ActuatorStateInterface>()->getHandle("joint1_motor");
  EXPECT_NEAR(motor.getVelocity(), 0.1295908897, 1e-9);
}

TEST_F(FirstOrderBackendTest, AJointNoRunningControllerCommandsGetsZeroEffort) {
  ASSERT_NO_FATAL_FAILURE(create("", MY_BACKENDS_SEED_URDF, "/one_DOF_robot", kSeedParams));
  hi::JointHandle joint1 = hw_->get<hi::EffortJointInterface>()->getHandle("joint1");
  for (int n = 0; n < 3; ++n) ASSERT_NO_FATAL_FAILURE(cycle(joint1, 1.0));  // nobody claimed joint1
  EXPECT_DOUBLE_EQ(state("joint1").getPosition(), 0.0);
  EXPECT_DOUBLE_EQ(state("joint1").getVelocity(), 0.0);
}

TEST_F(FirstOrderBackendTest, ABadParameterIsNamedWithItsKeyAndAnExample) {
  for (const char* bad : {"-1", "abc", "[0.1]"}) {
    try {
      create("", MY_BACKENDS_SEED_URDF, "/one_DOF_robot",
             std::string("{first_order: {time_constant: ") + bad + "}}");
      ADD_FAILURE() << "init accepted time_constant " << bad;
    } catch (const servoloop::ConfigError& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find("/one_DOF_robot/first_order/time_constant: expected a positive number (s)"),
                std::string::npos)
          << message;
      EXPECT_NE(message.find("e.g. 'time_constant: 0.05'"), std::string::npos) << message;
    }
  }
}

// --- a 10:1 transmission, joint limits and motor limits, for free ----------------------------

const std::string kWheelParams = "{sim: {time_step: 0.01}, first_order: {time_constant: 0.05, damping: 1.0}}";

TEST_F(FirstOrderBackendTest, VelocityCommandsAreSaturatedToTheUrdfLimitAndSeenThroughTheReduction) {
  ASSERT_NO_FATAL_FAILURE(create("", kWheelUrdf, "/wheel", kWheelParams));
  ASSERT_NO_FATAL_FAILURE(startController("VelocityJointInterface", "wheel"));
  hi::JointHandle wheel = hw_->get<hi::VelocityJointInterface>()->getHandle("wheel");

  // 2 rad/s asked, <limit velocity="1.0">: v* = 1 rad/s, τ = 0.05 s.
  for (int n = 0; n < 2; ++n) ASSERT_NO_FATAL_FAILURE(cycle(wheel, 2.0));
  const hi::JointStateHandle after = state("wheel");
  // v(0.02) = 1 − e^(−0.4) = 1 − 0.6703200460 = 0.3296799540 rad/s
  EXPECT_NEAR(after.getVelocity(), 0.3296799540, 1e-9);
  // q(0.02) = 0.02 − 0.05·0.3296799540 = 0.0035160023 rad
  EXPECT_NEAR(after.getPosition(), 0.0035160023, 1e-9);
  // The motor turns 10 times faster than the joint.
  const hi::ActuatorStateHandle motor = hw_->get<hi::ActuatorStateInterface>()->getHandle("wheel_motor");
  EXPECT_NEAR(motor.getVelocity(), 3.296799540, 1e-8);
  EXPECT_NEAR(motor.getPosition(), 0.035160023, 1e-8);
}

TEST_F(FirstOrderBackendTest, AWeakMotorBoundsTheSpeedItHoldsAgainstTheDamping) {
  // 0.05 N·m at the motor × 10 = 0.5 N·m at the joint; against 1 N·m·s/rad: 0.5 rad/s at most.
  ASSERT_NO_FATAL_FAILURE(create("", kWheelUrdf, "/wheel",
                                 "{sim: {time_step: 0.01}, first_order: {time_constant: 0.05, damping: 1.0},"
                                 " actuators: {wheel_motor: {max_effort: 0.05}}}"));
  ASSERT_NO_FATAL_FAILURE(startController("VelocityJointInterface", "wheel"));
  hi::JointHandle wheel = hw_->get<hi::VelocityJointInterface>()->getHandle("wheel");
  for (int n = 0; n < 2; ++n) ASSERT_NO_FATAL_FAILURE(cycle(wheel, 2.0));
  // v(0.02) = 0.5·(1 − e^(−0.4)) = 0.1648399770 rad/s
  EXPECT_NEAR(state("wheel").getVelocity(), 0.1648399770, 1e-9);
}

TEST_F(FirstOrderBackendTest, EmergencyStopZeroesVelocityCommandsAndTheJointCoastsDown) {
  ASSERT_NO_FATAL_FAILURE(create("", kWheelUrdf, "/wheel", kWheelParams));
  ASSERT_NO_FATAL_FAILURE(startController("VelocityJointInterface", "wheel"));
  hi::JointHandle wheel = hw_->get<hi::VelocityJointInterface>()->getHandle("wheel");
  for (int n = 0; n < 2; ++n) ASSERT_NO_FATAL_FAILURE(cycle(wheel, 1.0));
  sim_->setEmergencyStop(true);
  ASSERT_NO_FATAL_FAILURE(cycle(wheel, 1.0));  // the controller keeps asking; v* = 0
  const hi::JointStateHandle after = state("wheel");
  // From v0 = 0.3296799540, q0 = 0.0035160023 over 0.01 s towards 0:
  // v = v0·e^(−0.2) = 0.3296799540·0.8187307531 = 0.2699191170 rad/s
  // q = q0 + v0·0.05·(1 − e^(−0.2)) = 0.0035160023 + 0.0029880418 = 0.0065040442 rad
  EXPECT_NEAR(after.getVelocity(), 0.2699191170, 1e-9);
  EXPECT_NEAR(after.getPosition(), 0.0065040442, 1e-9);
}

TEST_F(FirstOrderBackendTest, PositionTargetsAreFollowedFromTheInitialPositionAndResetGoesBack) {
  // With the URDF's 1 rad/s, position saturation would let the target move by
  // only 0.01 rad per 0.01 s step; the YAML joint limits raise it out of the way.
  ASSERT_NO_FATAL_FAILURE(create("", kWheelUrdf, "/wheel",
                                 "{sim: {time_step: 0.01, initial_positions: {wheel: 0.2}},"
                                 " first_order: {time_constant: 0.05, damping: 1.0},"
                                 " joint_limits: {wheel: {has_velocity_limits: true, max_velocity: 100.0}}}"));
  EXPECT_DOUBLE_EQ(state("wheel").getPosition(), 0.2);
  ASSERT_NO_FATAL_FAILURE(startController("PositionJointInterface", "wheel"));
  hi::JointHandle wheel = hw_->get<hi::PositionJointInterface>()->getHandle("wheel");
  ASSERT_NO_FATAL_FAILURE(cycle(wheel, 1.0));
  const hi::JointStateHandle after = state("wheel");
  // τ·dq/dt = 1 − q from 0.2: q(0.01) = 1 − 0.8·e^(−0.2) = 0.3450153975 rad,
  // v = (1 − q)/τ = 0.6549846025 / 0.05 = 13.0996920492 rad/s
  EXPECT_NEAR(after.getPosition(), 0.3450153975, 1e-9);
  EXPECT_NEAR(after.getVelocity(), 13.0996920492, 1e-8);

  sim_->reset();
  EXPECT_DOUBLE_EQ(sim_->simTime().seconds, 0.0);
  EXPECT_DOUBLE_EQ(state("wheel").getPosition(), 0.2);
  EXPECT_DOUBLE_EQ(state("wheel").getVelocity(), 0.0);
}

}  // namespace
