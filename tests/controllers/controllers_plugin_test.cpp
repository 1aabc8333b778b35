// The controller plugins as a node uses them: found by the plugin loader in the
// build's plugin folder, created by type name and run by the controller
// manager from the seed's YAML.
#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "controller_test_support.hpp"
#include "servoloop/controller_manager/controller_factory.hpp"
#include "servoloop/controller_manager/controller_manager.hpp"
#include "servoloop/plugin/plugin_loader.hpp"

namespace servoloop::controllers {
namespace {

namespace cm = controller_manager;
using testing::TestJointsHW;
using Float64 = servoloop::std_msgs::Float64;
using JointStateMsg = servoloop::sensor_msgs::JointState;

// Controllers from the plugin loader, as the node's factory makes them.
class LoaderFactory : public cm::ControllerFactory {
 public:
  LoaderFactory() : loader_({std::filesystem::path(SERVOLOOP_PLUGIN_DIR)}) {}

  cm::ControllerPtr create(const std::string& type) override {
    if (!loader_.hasType(type)) return {};
    auto plugin = loader_.create<cm::ControllerBase>(type);
    servoloop::plugin::PluginDeleter deleter = plugin.get_deleter();
    return cm::ControllerPtr(plugin.release(), [deleter](cm::ControllerBase* c) { deleter(c); });
  }
  std::vector<std::string> types() override {
    std::vector<std::string> names;
    for (const auto& info : loader_.listTypes(cm::ControllerBase::kPluginKind)) names.push_back(info.type);
    return names;
  }
  servoloop::plugin::PluginLoader& loader() { return loader_; }

 private:
  servoloop::plugin::PluginLoader loader_;
};

TEST(ControllerPlugins, OneLibraryPerPackageProvidesEveryType) {
  LoaderFactory factory;
  EXPECT_TRUE(factory.loader().diagnostics().empty());
  std::map<std::string, std::string> library_of_type;
  for (const auto& info : factory.loader().listTypes("controller")) {
    library_of_type[info.type] = info.library.filename().string();
  }
  const std::map<std::string, std::string> expected = {
      {"joint_state_controller/JointStateController", "libjoint_state_controller.so"},
      {"effort_controllers/JointPositionController", "libeffort_controllers.so"},
      {"effort_controllers/JointVelocityController", "libeffort_controllers.so"},
      {"effort_controllers/JointEffortController", "libeffort_controllers.so"},
      {"effort_controllers/JointGroupEffortController", "libeffort_controllers.so"},
      {"effort_controllers/JointGroupPositionController", "libeffort_controllers.so"},
      {"position_controllers/JointPositionController", "libposition_controllers.so"},
      {"position_controllers/JointGroupPositionController", "libposition_controllers.so"},
      {"velocity_controllers/JointVelocityController", "libvelocity_controllers.so"},
      {"velocity_controllers/JointGroupVelocityController", "libvelocity_controllers.so"},
      {"minimal_joint_controller/MinimalJointController", "libminimal_joint_controller.so"},
      {"position_controllers/JointTrajectoryController", "libjoint_trajectory_controller.so"},
      {"velocity_controllers/JointTrajectoryController", "libjoint_trajectory_controller.so"},
      {"effort_controllers/JointTrajectoryController", "libjoint_trajectory_controller.so"},
      {"position_controllers/GripperActionController", "libgripper_action_controller.so"},
      {"effort_controllers/GripperActionController", "libgripper_action_controller.so"},
      {"diff_drive_controller/DiffDriveController", "libdiff_drive_controller.so"},
      {"imu_sensor_controller/ImuSensorController", "libimu_sensor_controller.so"},
      {"force_torque_sensor_controller/ForceTorqueSensorController", "libforce_torque_sensor_controller.so"},
  };
  for (const auto& [type, library] : expected) {
    ASSERT_TRUE(library_of_type.count(type)) << type;
    EXPECT_EQ(library_of_type[type], library) << type;
  }
}

class SeedThroughManager : public ::testing::Test {
 protected:
  SeedThroughManager() {
    cm::ControllerContext context;
    context.robot_namespace = "/one_DOF_robot";
    context.topics = &bus;
    context.robot_model = testing::seedRobotModel();
    params = testing::seedControllerParams();
    manager = std::make_unique<cm::ControllerManager>(&hw, std::make_shared<LoaderFactory>(),
                                                      cm::ControllerManager::lookupIn(params), context,
                                                      1000.0);
  }
  ~SeedThroughManager() override { manager.reset(); }

  void start(const std::vector<std::string>& names) {
    for (const auto& name : names) ASSERT_TRUE(manager->loadController(name)) << name;
    cm::SwitchRequest request;
    request.start_controllers = names;
    ASSERT_TRUE(manager->requestSwitch(request));
    cycle();  // the switch is carried out at the start of this cycle
    ASSERT_FALSE(manager->switchPending());
  }
  void cycle() {
    ++cycles;
    manager->update(Time(0.001 * cycles), Duration(0.001));
  }

  servoloop::realtime::TopicBus bus;
  TestJointsHW hw{{"joint1"}};
  YAML::Node params;
  std::unique_ptr<cm::ControllerManager> manager;
  int cycles = 0;
};

TEST_F(SeedThroughManager, PositionControllerAndJointStatesFromTheSeedYaml) {
  std::vector<JointStateMsg> joint_states;
  auto subscription = bus.subscribe<JointStateMsg>(
      "/one_DOF_robot/joint_states", [&](const JointStateMsg& msg) { joint_states.push_back(msg); });
  hw.position[0] = 0.5;
  start({"joint_state_controller", "joint1_position_controller"});
  bus.publish("/one_DOF_robot/joint1_position_controller/command", Float64{1.0});
  cycle();  // the controllers' first update, 1 ms after starting

  // The seed's PID (p 10, i 10, d 10, i_clamp ±10) on error 0.5 with dt 1 ms.
  const double error = 0.5, dt = 0.001;
  EXPECT_NEAR(hw.effort_command[0], 10.0 * error + std::min(10.0 * dt * error, 10.0) + 10.0 * error / dt,
              1e-9);

  for (int k = 0; k < 39; ++k) cycle();  // 40 updates at 1 kHz with publish_rate 50
  bus.flush();
  ASSERT_EQ(joint_states.size(), 2u);
  EXPECT_EQ(joint_states[0].name, (std::vector<std::string>{"joint1"}));
  EXPECT_DOUBLE_EQ(joint_states[0].position[0], 0.5);
  EXPECT_NEAR(joint_states[1].stamp - joint_states[0].stamp, 0.020, 1e-12);
}

TEST_F(SeedThroughManager, RawPdRunsAtItsOwnRateWithOrWithoutTheManagersHelp) {
  params["pd_default"]["type"] = "minimal_joint_controller/MinimalJointController";
  params["pd_rate"]["type"] = "minimal_joint_controller/MinimalJointController";
  params["pd_rate"]["update_rate"] = 100;  // here the manager runs it every 10th cycle
  std::map<std::string, int> effort_messages;
  std::vector<servoloop::realtime::Subscription> subscriptions;
  for (const std::string name : {"pd_default", "pd_rate"}) {
    subscriptions.push_back(bus.subscribe<Float64>(
        "/one_DOF_robot/" + name + "/jnt_trq", [&effort_messages, name](const Float64&) { ++effort_messages[name]; }));
  }
  ASSERT_TRUE(manager->loadController("pd_rate"));

  // Runs 100 cycles with the joint moving every cycle; returns how often the
  // effort command changed (once per control update: it is held in between).
  const auto effortChanges = [&] {
    int changes = 0;
    double effort = hw.effort_command[0];
    for (int k = 0; k < 100; ++k) {
      hw.position[0] = 0.001 * cycles;
      cycle();
      if (hw.effort_command[0] != effort) ++changes;
      effort = hw.effort_command[0];
    }
    return changes;
  };

  start({"pd_default"});  // no update_rate parameter: the controller keeps its default 100 Hz itself
  EXPECT_EQ(effortChanges(), 10);
  cm::SwitchRequest request;
  request.start_controllers = {"pd_rate"};
  request.stop_controllers = {"pd_default"};
  ASSERT_TRUE(manager->requestSwitch(request));
  cycle();
  ASSERT_FALSE(manager->switchPending());
  EXPECT_EQ(effortChanges(), 10);
  bus.flush();
  EXPECT_EQ(effort_messages["pd_default"], 10);
  EXPECT_EQ(effort_messages["pd_rate"], 10);
}

// The sensor controllers from the plugin loader, run by the manager: two
// controllers reading the same IMU start together (sensors are never claimed).
TEST(SensorControllerPlugins, PublishEverySensorThroughTheManager) {
  const YAML::Node params = YAML::Load(R"(
imu_sensor_controller: {type: imu_sensor_controller/ImuSensorController, publish_rate: 100}
imu_logger: {type: imu_sensor_controller/ImuSensorController, publish_rate: 10}
force_torque_sensor_controller: {type: force_torque_sensor_controller/ForceTorqueSensorController, publish_rate: 50}
)");
  servoloop::realtime::TopicBus bus;
  testing::TestSensorsHW hw;
  hw.addImu("imu", "imu_link").angular_velocity = {0.0, 0.0, 0.5};
  hw.addForceTorque("wrist_ft", "wrist_ft_link").force = {0.0, 0.0, -9.81};
  std::vector<servoloop::sensor_msgs::Imu> imu;
  std::vector<servoloop::geometry_msgs::WrenchStamped> wrist;
  auto imu_sub = bus.subscribe<servoloop::sensor_msgs::Imu>("/robot/imu", [&](const auto& m) { imu.push_back(m); });
  auto wrist_sub = bus.subscribe<servoloop::geometry_msgs::WrenchStamped>(
      "/robot/wrist_ft", [&](const auto& m) { wrist.push_back(m); });
  cm::ControllerContext context;
  context.robot_namespace = "/robot";
  context.topics = &bus;
  cm::ControllerManager manager(&hw, std::make_shared<LoaderFactory>(), cm::ControllerManager::lookupIn(params),
                                context, 1000.0);
  cm::SwitchRequest request;
  for (const char* name : {"imu_sensor_controller", "imu_logger", "force_torque_sensor_controller"}) {
    ASSERT_TRUE(manager.loadController(name)) << name;
    request.start_controllers.push_back(name);
  }
  ASSERT_TRUE(manager.requestSwitch(request));
  for (int k = 1; k <= 100; ++k) manager.update(Time(0.001 * k), Duration(0.001));
  ASSERT_FALSE(manager.switchPending());
  bus.flush();
  // Started in the first cycle, first published in the second: 10 at 100 Hz
  // and 1 at 10 Hz in the 99 updates; 5 wrenches at 50 Hz.
  EXPECT_EQ(imu.size(), 11u);
  ASSERT_EQ(wrist.size(), 5u);
  EXPECT_EQ(imu.front().frame_id, "imu_link");
  EXPECT_EQ(imu.front().angular_velocity.z, 0.5);
  EXPECT_EQ(wrist.front().frame_id, "wrist_ft_link");
  EXPECT_EQ(wrist.front().wrench.force.z, -9.81);
}

// A 6-joint arm's controller YAML written the way arm vendors write theirs
// (a UR-style file: YAML anchors for the rate and the joint list, per-joint
// gains and constraints, an effort trajectory controller next to a group
// controller on the same joints) loads unchanged through the plugin loader,
// and the trajectory controller drives its joints to a trajectory's end.
TEST(ArmControllerYaml, LoadsUnchangedAndFollowsATrajectory) {
  const YAML::Node params = YAML::Load(R"(
joint_state_controller:
  type: joint_state_controller/JointStateController
  publish_rate: &loop_hz 125
arm_controller:
  type: effort_controllers/JointTrajectoryController
  joints: &arm_joints
    - shoulder_yaw
    - shoulder_pitch
    - elbow
    - wrist_pitch
    - wrist_roll
    - flange
  gains:
    shoulder_yaw: {p: 4000, d: 200, i: 1, i_clamp: 1}
    shoulder_pitch: {p: 10000, d: 200, i: 1, i_clamp: 1}
    elbow: {p: 2000, d: 20, i: 1, i_clamp: 1}
    wrist_pitch: {p: 500, d: 1, i: 1, i_clamp: 1}
    wrist_roll: {p: 500, d: 1, i: 1, i_clamp: 1}
    flange: {p: 10, d: 0.1, i: 0, i_clamp: 1}
  constraints:
    goal_time: 0.6
    stopped_velocity_tolerance: 0.05
    shoulder_yaw: {trajectory: 0.1, goal: 0.1}
    shoulder_pitch: {trajectory: 0.1, goal: 0.1}
    elbow: {trajectory: 0.1, goal: 0.1}
    wrist_pitch: {trajectory: 0.1, goal: 0.1}
    wrist_roll: {trajectory: 0.1, goal: 0.1}
    flange: {trajectory: 0.1, goal: 0.1}
  stop_trajectory_duration: 0.5
  state_publish_rate: *loop_hz
  action_monitor_rate: 10
group_effort_controller:
  type: effort_controllers/JointGroupEffortController
  joints: *arm_joints
)");
  const std::vector<std::string> joints = {"shoulder_yaw", "shoulder_pitch", "elbow", "wrist_pitch", "wrist_roll", "flange"};
  servoloop::realtime::TopicBus bus;
  TestJointsHW hw(joints);
  cm::ControllerContext context;
  context.robot_namespace = "/arm";
  context.topics = &bus;
  cm::ControllerManager manager(&hw, std::make_shared<LoaderFactory>(), cm::ControllerManager::lookupIn(params),
                                context, 1000.0);
  for (const char* name : {"joint_state_controller", "arm_controller", "group_effort_controller"}) {
    ASSERT_TRUE(manager.loadController(name)) << name;
  }
  cm::SwitchRequest request;
  request.start_controllers = {"joint_state_controller", "arm_controller"};
  ASSERT_TRUE(manager.requestSwitch(request));
  int cycles = 0;
  const auto cycle = [&] {
    ++cycles;
    manager.update(Time(0.001 * cycles), Duration(0.001));
    // Each joint a free unit inertia (1 kg·m²), semi-implicit Euler.
    for (std::size_t j = 0; j < joints.size(); ++j) {
      hw.velocity[j] += 0.001 * hw.effort_command[j];
      hw.position[j] += 0.001 * hw.velocity[j];
    }
  };
  cycle();
  ASSERT_FALSE(manager.switchPending());

  servoloop::trajectory_msgs::JointTrajectory msg;
  msg.joint_names = joints;
  servoloop::trajectory_msgs::JointTrajectoryPoint point;
  point.positions = {0.3, -0.2, 0.25, 0.1, -0.1, 0.05};
  point.velocities.assign(6, 0.0);
  point.time_from_start = 1.0;
  msg.points = {point};
  bus.publish("/arm/arm_controller/command", msg);
  bus.flush();
  for (int k = 0; k < 2000; ++k) cycle();
  // On a unit inertia the first three joints' gains are damped enough
  // (ζ = 1.6, 1.0, 0.22) to settle within a second of the end; the wrist
  // gains are tuned for far smaller inertias.
  for (std::size_t j = 0; j < 3; ++j) EXPECT_NEAR(hw.position[j], point.positions[j], 0.01) << joints[j];
}

}  // namespace
}  // namespace servoloop::controllers
