// ROS 1's own tools against a servoloop node through `servoloop ros1-bridge`:
// a private roscore on a free port, the seed robot simulated on bullet, then
// rostopic, rosservice, rosparam and rosbag as a ROS user types them.
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <csignal>
#include <signal.h>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_client_support.hpp"

namespace servoloop::cli::testing {
namespace {

namespace fs = std::filesystem;
using servoloop::testing::ChildProcess;
using servoloop::testing::ProcessOptions;
using servoloop::testing::ProcessResult;
using ::testing::HasSubstr;

const fs::path kOneDof = fs::path(SERVOLOOP_SOURCE_DIR) / "robots" / "one_dof";
constexpr const char* kCommandTopic = "/one_DOF_robot/joint1_position_controller/command";

int freeTcpPort() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = 0;
  socklen_t length = sizeof(address);
  if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
    if (fd >= 0) ::close(fd);
    return 0;
  }
  const int port = ntohs(address.sin_port);
  ::close(fd);
  return port;
}

// A ROS tool (roscore, rostopic, rosservice, rosparam, rosbag) by its path.
std::string ros(const std::string& tool) { return std::string(SERVOLOOP_ROS1_BIN_DIR) + "/" + tool; }

// A program of a ROS package (/usr/lib/<package>/<program>).
std::string ros_lib(const std::string& program) {
  return (fs::path(SERVOLOOP_ROS1_BIN_DIR) / ".." / "lib" / program).lexically_normal().string();
}

// The number after "<name>: " in rostopic's YAML output.
std::optional<double> numberField(const std::string& echo, const std::string& name) {
  const std::regex pattern("\\n" + name + ": ([-+0-9.eE]+)");
  std::smatch match;
  if (!std::regex_search(echo, match, pattern)) return std::nullopt;
  return std::stod(match[1].str());
}

// The first "position: [x]" of a rostopic echo of a JointState.
std::optional<double> firstPosition(const std::string& echo) {
  static const std::regex pattern(R"(position: \[([-+0-9.eE]+))");
  std::smatch match;
  if (!std::regex_search(echo, match, pattern)) return std::nullopt;
  return std::stod(match[1].str());
}

class Ros1BridgeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const int port = freeTcpPort();
    ASSERT_NE(port, 0);
    // ROS's tools and the bridge read these; the test's children inherit them.
    setenv("ROS_MASTER_URI", ("http://localhost:" + std::to_string(port)).c_str(), 1);
    setenv("ROS_HOSTNAME", "localhost", 1);
    setenv("ROS_HOME", (run_.scratch() / "ros_home").c_str(), 1);
    setenv("ROS_LOG_DIR", (run_.scratch() / "ros_log").c_str(), 1);
    // rosservice and rostopic read controller_manager_msgs and control_msgs
    // with no step of the user's: the bridge names their folder in the
    // user's site-packages (here the test's own home), and nothing else
    // points Python there.
    setenv("HOME", (run_.scratch() / "home").c_str(), 1);
    unsetenv("PYTHONPATH");
    unsetenv("PYTHONUSERBASE");
    unsetenv("PYTHONNOUSERSITE");

    // In a session of its own, so TearDown can end the master and rosout it
    // starts even if roscore itself does not stop them.
    roscore_.emplace(std::vector<std::string>{"/usr/bin/setsid", ros("roscore"), "-p", std::to_string(port)},
                     options("roscore"));
    ASSERT_TRUE(waitUntil([&] { return run({ros("rosparam"), "get", "/rosdistro"}).status == 0; }, 60.0))
        << roscore_->currentOut() << roscore_->currentErr();

    std::vector<std::string> launch = {"launch", (kOneDof / launchFile()).string(), "--rtf", realTimeFactor()};
    if (bridgeFromLaunch()) launch.emplace_back("--ros1-bridge");
    node_.emplace(launch, run_.scratch());
    ASSERT_TRUE(waitUntil([&] {
      const CliResult list = runCli({"control", "list", "-N", "/one_DOF_robot"}, run_.scratch());
      return list.status == 0 && list.out.find("( running )") != std::string::npos;
    }, 60.0)) << node_->currentErr();

    if (bridgeFromLaunch()) {
      ASSERT_TRUE(waitUntil([&] {
        return run({ros("rostopic"), "list"}).out.find("/one_DOF_robot/joint_states") != std::string::npos;
      }, 30.0)) << node_->currentErr();
    } else {
      startBridge();
    }
  }

  // Whether `servoloop launch --ros1-bridge` starts the bridge (else the test
  // runs `servoloop ros1-bridge` itself).
  virtual bool bridgeFromLaunch() const { return false; }
  virtual std::string launchFile() const { return "one_dof_w_jnt_ctl.launch.yaml"; }
  virtual std::string realTimeFactor() const { return "5"; }

  void TearDown() override {
    // roscore is a launcher: SIGINT lets it stop the master and rosout it started.
    for (ChildProcess* child : {static_cast<ChildProcess*>(bridge_ ? &*bridge_ : nullptr),
                                static_cast<ChildProcess*>(node_ ? &*node_ : nullptr),
                                roscore_ ? &*roscore_ : nullptr}) {
      if (child == nullptr) continue;
      child->signal(SIGINT);
      child->wait(20.0);
    }
    if (roscore_) ::kill(-roscore_->pid(), SIGKILL);  // whatever of its session is left
  }

  void startBridge() {
    bridge_.emplace(std::vector<std::string>{SERVOLOOP_CLI_EXE, "ros1-bridge", "-N", "/one_DOF_robot"}, options("bridge"));
    ASSERT_TRUE(bridge_->waitForOutput("bridging /one_DOF_robot", 30.0)) << bridge_->currentErr();
  }

  ProcessOptions options(const std::string& name) {
    ProcessOptions out;
    out.output_dir = run_.scratch() / name;
    fs::create_directories(out.output_dir);
    return out;
  }

  ProcessResult run(const std::vector<std::string>& argv, double timeout_s = 30.0) {
    return servoloop::testing::runProcess(argv, options("tool"), timeout_s);
  }

  // An effort gripper controller on the seed's joint, configured with rosparam
  // only: stiffness 500 N·m/rad against at most 9.81 · 0.5 · sin(0.3) = 1.45
  // N·m of gravity leaves 0.003 rad of error at 0.3 rad, inside the 0.01 rad
  // goal tolerance.
  void loadGripperParametersIntoRos() {
    const fs::path yaml = run_.scratch() / "gripper.yaml";
    std::ofstream(yaml) << "joint1_gripper_controller:\n"
                           "  type: effort_controllers/GripperActionController\n"
                           "  joint: joint1\n"
                           "  gains: {joint1: {p: 500.0, d: 20.0}}\n"
                           "  goal_tolerance: 0.01\n";
    ASSERT_EQ(run({ros("rosparam"), "load", yaml.string(), "/one_DOF_robot"}).status, 0);
  }

  // Loads `controller` and starts it in place of the seed's position
  // controller through ros_control's services, as a ROS user would.
  void loadAndStartThroughRos(const std::string& controller) {
    const std::string services = "/one_DOF_robot/controller_manager/";
    EXPECT_THAT(run({ros("rosservice"), "call", services + "load_controller", "name: " + controller}).out,
                HasSubstr("ok: True"));
    EXPECT_THAT(run({ros("rosservice"), "call", services + "switch_controller",
                     "{start_controllers: [" + controller + "], stop_controllers: [joint1_position_controller], "
                     "strictness: 2}"}).out,
                HasSubstr("ok: True"));
  }

  // A goal as actionlib sends it (rostopic pub on <action>/goal, once the
  // bridge serves the action), and the <action>/result that ends it, as
  // rostopic echo sees it (its subscription registered before the goal goes).
  ProcessResult sendGoalAndWaitForResult(const std::string& action, const std::string& type, const std::string& goal) {
    const bool served =
        waitUntil([&] { return run({ros("rostopic"), "list"}).out.find(action + "/goal") != std::string::npos; }, 30.0);
    EXPECT_TRUE(served) << action << " not served";
    ChildProcess result({ros("rostopic"), "echo", "-n", "1", action + "/result"}, options("result"));
    const bool subscribed = waitUntil([&] {
      static const std::regex registered(R"(Subscribers:\s*\n \* /rostopic)");
      return std::regex_search(run({ros("rostopic"), "info", action + "/result"}).out, registered);
    }, 20.0);
    EXPECT_TRUE(subscribed);
    const ProcessResult sent = run({ros("rostopic"), "pub", "-1", action + "/goal", type, goal});
    EXPECT_EQ(sent.status, 0) << sent.err;
    return result.wait(60.0);
  }

  bool nodeAnswers() {
    const CliResult list = runCli({"control", "list", "-N", "/one_DOF_robot"}, run_.scratch());
    return list.status == 0 && list.out.find("joint1_position_controller") != std::string::npos;
  }

  ScopedRunDir run_;
  std::optional<ChildProcess> roscore_;
  std::optional<CliProcess> node_;
  std::optional<ChildProcess> bridge_;
};

TEST_F(Ros1BridgeTest, RosToolsDriveAndWatchTheSeedRobot) {
  // rostopic echo: the node's joint states, stamped with simulated time.
  const ProcessResult echo = run({ros("rostopic"), "echo", "-n", "1", "/one_DOF_robot/joint_states"});
  ASSERT_EQ(echo.status, 0) << echo.err;
  EXPECT_THAT(echo.out, HasSubstr("- joint1"));

  // rosservice: ros_control's list_controllers, with ros_control's names.
  const ProcessResult list = run({ros("rosservice"), "call", "/one_DOF_robot/controller_manager/list_controllers"});
  ASSERT_EQ(list.status, 0) << list.err;
  EXPECT_THAT(list.out, HasSubstr("name: \"joint_state_controller\""));
  EXPECT_THAT(list.out, HasSubstr("name: \"joint1_position_controller\""));
  EXPECT_THAT(list.out, HasSubstr("type: \"effort_controllers/JointPositionController\""));
  EXPECT_THAT(list.out, HasSubstr("hardware_interface: \"hardware_interface::EffortJointInterface\""));
  EXPECT_THAT(list.out, Not(HasSubstr("state: \"stopped\"")));

  // rosparam: simulated time, the robot's URDF, the controller parameters.
  EXPECT_THAT(run({ros("rosparam"), "get", "/use_sim_time"}).out, HasSubstr("true"));
  EXPECT_THAT(run({ros("rosparam"), "get", "/one_DOF_robot/robot_description"}).out, HasSubstr("joint1"));
  EXPECT_THAT(run({ros("rosparam"), "get", "/one_DOF_robot/joint1_position_controller/type"}).out,
              HasSubstr("effort_controllers/JointPositionController"));

  // The seed's own command, as its tutorial types it, moves the joint to 1 rad
  // (the PD controller's set point), seen by rostopic echo.
  ChildProcess pub({ros("rostopic"), "pub", "-r", "10", kCommandTopic, "std_msgs/Float64", "1.0"}, options("pub"));
  // Settled: three readings in a row within 0.01 rad (the PID's integral
  // term still moves it across 1.0 on the way).
  double last = 0.0;
  int settled = 0;
  EXPECT_TRUE(waitUntil([&] {
    const auto position = firstPosition(run({ros("rostopic"), "echo", "-n", "1", "/one_DOF_robot/joint_states"}).out);
    if (position) last = *position;
    settled = position && std::abs(*position - 1.0) < 0.01 ? settled + 1 : 0;
    return settled >= 3;
  }, 120.0)) << "joint1 at " << last;

  // The controller's state as ROS's control_msgs/JointControllerState: the set
  // point is the command, the process value the joint's position.
  const ProcessResult state = run({ros("rostopic"), "echo", "-n", "1", "/one_DOF_robot/joint1_position_controller/state"});
  EXPECT_EQ(numberField(state.out, "set_point"), 1.0) << state.out;
  EXPECT_NEAR(numberField(state.out, "process_value").value_or(0.0), 1.0, 0.02) << state.out;

  // robot_state_publisher, started as ROS users start it in the robot's
  // namespace, turns the bridged joint states and robot_description into /tf:
  // link1 → link2 is joint1's rotation about y, the quaternion
  // (0, sin(q/2), 0, cos(q/2)) with q = 1 rad within the 0.01 rad above.
  ChildProcess state_publisher({ros_lib("robot_state_publisher/robot_state_publisher"), "__ns:=/one_DOF_robot"},
                               options("robot_state_publisher"));
  std::optional<double> rotation_y;
  EXPECT_TRUE(waitUntil([&] {
    const ProcessResult tf = run({ros("rostopic"), "echo", "-n", "1", "/tf"}, 10.0);
    static const std::regex pattern(R"(child_frame_id: \"link2\"[\s\S]*?rotation:\s*x: [-0-9.e]+\s*y: ([-0-9.e]+))");
    std::smatch match;
    if (!std::regex_search(tf.out, match, pattern)) return false;
    rotation_y = std::stod(match[1].str());
    return true;
  }, 60.0)) << "no link1 → link2 transform on /tf";
  if (rotation_y) {
    EXPECT_NEAR(*rotation_y, std::sin(0.5), 0.005);
  }
  state_publisher.signal(SIGINT);
  pub.signal(SIGINT);

  // rosbag: 5 s of simulated time hold 5 s × 50 Hz (joint_state_controller's
  // publish_rate) joint states. rosbag ends the window by /clock, which the
  // bridge publishes every 5 ms of wall time (25 ms of simulated time at
  // --rtf 5) and the tools connect while it runs, so the count may be off by a
  // few messages at either end (250 ± 5 is allowed); inside the
  // window no message is lost or repeated: the stamps step by exactly 20 ms.
  const fs::path bag = run_.scratch() / "joint_states.bag";
  const ProcessResult record =
      run({ros("rosbag"), "record", "--duration=5", "-O", bag.string(), "/one_DOF_robot/joint_states"}, 120.0);
  ASSERT_EQ(record.status, 0) << record.err;
  const ProcessResult rows = run({ros("rostopic"), "echo", "-p", "-b", bag.string(), "/one_DOF_robot/joint_states"});
  ASSERT_EQ(rows.status, 0) << rows.err;
  std::vector<long long> stamps_ns;
  std::istringstream lines(rows.out);
  std::string line;
  std::getline(lines, line);  // %time,field.header.seq,field.header.stamp,...
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    std::string received, seq, stamp;
    std::getline(fields, received, ',');
    std::getline(fields, seq, ',');
    std::getline(fields, stamp, ',');
    if (!stamp.empty()) stamps_ns.push_back(std::stoll(stamp));
  }
  EXPECT_GE(stamps_ns.size(), 245u);
  EXPECT_LE(stamps_ns.size(), 255u);
  for (std::size_t i = 1; i < stamps_ns.size(); ++i) {
    ASSERT_EQ(stamps_ns[i] - stamps_ns[i - 1], 20'000'000) << "message " << i << " of " << stamps_ns.size();
  }
}

TEST_F(Ros1BridgeTest, SwitchControllerFollowsRosControlSemantics) {
  const std::string service = "/one_DOF_robot/controller_manager/switch_controller";
  // STRICT with a controller that does not exist: ok False, nothing changes.
  const ProcessResult refused =
      run({ros("rosservice"), "call", service, "{start_controllers: [no_such_controller], stop_controllers: [joint1_position_controller], strictness: 2}"});
  ASSERT_EQ(refused.status, 0) << refused.err;
  EXPECT_THAT(refused.out, HasSubstr("ok: False"));
  EXPECT_THAT(runCli({"control", "list", "-N", "/one_DOF_robot"}, run_.scratch()).out,
              Not(HasSubstr("( stopped )")));

  const ProcessResult stopped =
      run({ros("rosservice"), "call", service, "{start_controllers: [], stop_controllers: [joint1_position_controller], strictness: 2}"});
  EXPECT_THAT(stopped.out, HasSubstr("ok: True"));
  EXPECT_THAT(runCli({"control", "list", "-N", "/one_DOF_robot"}, run_.scratch()).out,
              HasSubstr("joint1_position_controller - effort_controllers/JointPositionController ( stopped )"));
  const ProcessResult listed = run({ros("rosservice"), "call", "/one_DOF_robot/controller_manager/list_controllers"});
  EXPECT_THAT(listed.out, HasSubstr("state: \"stopped\""));

  // list_controller_types: every controller type on the plugin path.
  const ProcessResult types = run({ros("rosservice"), "call", "/one_DOF_robot/controller_manager/list_controller_types"});
  EXPECT_THAT(types.out, HasSubstr("effort_controllers/JointPositionController"));
  EXPECT_THAT(types.out, HasSubstr("controller_interface::ControllerBase"));

  // load_controller of a name with no configuration: ok False.
  EXPECT_THAT(run({ros("rosservice"), "call", "/one_DOF_robot/controller_manager/load_controller", "name: not_configured"}).out,
              HasSubstr("ok: False"));
}

// Gazebo's world services, as a ROS user calls them, reach the node's world:
// pause, set_model_configuration, step (servoloop's own command), reset.
// The joint is read back through /gazebo/get_joint_properties, i.e. from the
// joint states the node publishes while it steps.
TEST_F(Ros1BridgeTest, GazeboWorldServicesPauseSetConfigurationAndReset) {
  const auto joint1Position = [&]() -> std::optional<double> {
    static const std::regex pattern(R"(position: \[([-+0-9.eE]+))");
    const std::string out = run({ros("rosservice"), "call", "/gazebo/get_joint_properties", "joint_name: joint1"}).out;
    std::smatch match;
    if (!std::regex_search(out, match, pattern)) return std::nullopt;
    return std::stod(match[1].str());
  };
  const ProcessResult pause = run({ros("rosservice"), "call", "/gazebo/pause_physics"});
  ASSERT_EQ(pause.status, 0) << pause.err;
  EXPECT_THAT(runCli({"world", "state"}, run_.scratch()).out, HasSubstr("paused at t ="));

  const ProcessResult set = run({ros("rosservice"), "call", "/gazebo/set_model_configuration",
                                 "{model_name: one_DOF_robot, joint_names: [joint1], joint_positions: [0.7]}"});
  ASSERT_EQ(set.status, 0) << set.err;
  EXPECT_THAT(set.out, HasSubstr("success: True"));
  EXPECT_THAT(run({ros("rosservice"), "call", "/gazebo/set_model_configuration",
                   "{model_name: one_DOF_robot, joint_names: [elbow], joint_positions: [0.7]}"}).out,
              AllOf(HasSubstr("success: False"), HasSubstr("elbow")));
  // 40 steps: the joint states of two 50 Hz cycles; in 40 ms the joint,
  // held by its position controller, moves by far less than 0.05 rad.
  ASSERT_EQ(runCli({"world", "step", "40"}, run_.scratch()).status, 0);
  EXPECT_TRUE(waitUntil([&] {
    const auto position = joint1Position();
    return position && std::abs(*position - 0.7) < 0.05;
  }, 20.0)) << "joint1 is at " << joint1Position().value_or(NAN);

  const ProcessResult reset = run({ros("rosservice"), "call", "/gazebo/reset_simulation"});
  ASSERT_EQ(reset.status, 0) << reset.err;
  EXPECT_THAT(runCli({"world", "state"}, run_.scratch()).out, HasSubstr("paused at t = 0 s (0 physics steps)"));
  ASSERT_EQ(runCli({"world", "step", "40"}, run_.scratch()).status, 0);
  EXPECT_TRUE(waitUntil([&] {
    const auto position = joint1Position();
    return position && std::abs(*position) < 1e-3;
  }, 20.0)) << "after the reset joint1 is at " << joint1Position().value_or(NAN);

  ASSERT_EQ(run({ros("rosservice"), "call", "/gazebo/unpause_physics"}).status, 0);
  EXPECT_THAT(runCli({"world", "state"}, run_.scratch()).out, HasSubstr("running at t ="));
}

// Gazebo's model services and /gazebo/model_states, as a ROS user calls
// them, on a paused world (so a pose read back is the pose set): a
// box spawned from its URDF text as spawn_model -urdf sends it (robot
// namespace "/", spawn_model's default), moved with set_model_state (only a
// position given: the orientation left at zeros is upright, as in Gazebo),
// falling for 0.1 s once stepped, then deleted.
TEST_F(Ros1BridgeTest, GazeboModelServicesSpawnSetAndDelete) {
  // (x, y, z) of get_model_state's pose, or nullopt when the call fails.
  const auto modelPosition = [&](const std::string& model) -> std::optional<std::array<double, 3>> {
    static const std::regex pattern(R"(position:\s*x: ([-+0-9.eE]+)\s*y: ([-+0-9.eE]+)\s*z: ([-+0-9.eE]+))");
    const std::string out = run({ros("rosservice"), "call", "/gazebo/get_model_state", "{model_name: " + model + "}"}).out;
    std::smatch match;
    if (out.find("success: True") == std::string::npos || !std::regex_search(out, match, pattern)) return std::nullopt;
    return std::array<double, 3>{std::stod(match[1].str()), std::stod(match[2].str()), std::stod(match[3].str())};
  };
  const auto expectAt = [&](const std::string& model, double x, double y, double z) {
    const auto position = modelPosition(model);
    ASSERT_TRUE(position.has_value()) << model << " not found";
    EXPECT_NEAR((*position)[0], x, 1e-9);
    EXPECT_NEAR((*position)[1], y, 1e-9);
    EXPECT_NEAR((*position)[2], z, 1e-9);
  };
  // The world's models, published by the node and bridged (before the pause:
  // a paused world publishes none).
  EXPECT_TRUE(waitUntil([&] {
    return run({ros("rostopic"), "echo", "-n", "1", "/gazebo/model_states"}, 10.0).out.find("- one_DOF_robot") !=
           std::string::npos;
  }, 30.0));
  ASSERT_EQ(run({ros("rosservice"), "call", "/gazebo/pause_physics"}).status, 0);

  // A free 0.2 m, 1 kg box, 1 m up at x = 2.
  const std::string crate =
      "<robot name=\"crate\"><link name=\"base\"><inertial><mass value=\"1.0\"/>"
      "<inertia ixx=\"0.0067\" ixy=\"0\" ixz=\"0\" iyy=\"0.0067\" iyz=\"0\" izz=\"0.0067\"/></inertial>"
      "<collision><geometry><box size=\"0.2 0.2 0.2\"/></geometry></collision></link></robot>";
  const std::string spawn = "/gazebo/spawn_urdf_model";
  const ProcessResult spawned =
      run({ros("rosservice"), "call", spawn,
           "{model_name: crate, model_xml: '" + crate + "', robot_namespace: '/', initial_pose: {position: {x: 2.0, "
           "y: 0.0, z: 1.0}, orientation: {x: 0.0, y: 0.0, z: 0.0, w: 1.0}}, reference_frame: world}"},
          90.0);
  ASSERT_EQ(spawned.status, 0) << spawned.err;
  ASSERT_THAT(spawned.out, HasSubstr("success: True"));
  expectAt("crate", 2.0, 0.0, 1.0);
  EXPECT_THAT(run({ros("rosservice"), "call", spawn, "{model_name: crate2, model_xml: ''}"}).out,
              AllOf(HasSubstr("success: False"), HasSubstr("model_xml is empty")));
  EXPECT_THAT(run({ros("rosservice"), "call", spawn,
                   "{model_name: crate2, model_xml: '" + crate + "', reference_frame: 'crate::base'}"}).out,
              AllOf(HasSubstr("success: False"), HasSubstr("crate::base")));

  const std::string set = "/gazebo/set_model_state";
  const ProcessResult moved = run({ros("rosservice"), "call", set,
                                   "{model_state: {model_name: crate, pose: {position: {x: 1.0, y: -0.5, z: 3.0}}, "
                                   "reference_frame: world}}"});
  ASSERT_EQ(moved.status, 0) << moved.err;
  EXPECT_THAT(moved.out, HasSubstr("success: True"));
  expectAt("crate", 1.0, -0.5, 3.0);
  EXPECT_THAT(run({ros("rosservice"), "call", set, "{model_state: {model_name: crate, reference_frame: 'crate::base'}}"}).out,
              AllOf(HasSubstr("success: False"), HasSubstr("crate::base")));
  // (rosservice wraps the long status message: the words checked are short.)
  EXPECT_THAT(run({ros("rosservice"), "call", set, "{model_state: {model_name: one_DOF_robot}}"}).out,
              AllOf(HasSubstr("success: False"), HasSubstr("has a fixed")));
  // 100 steps of 1 ms from rest: free fall by g t^2 / 2 = 49 mm (semi-implicit
  // Euler: within g t dt / 2 = 0.5 mm of it).
  ASSERT_EQ(runCli({"world", "step", "100"}, run_.scratch()).status, 0);
  const auto fallen = modelPosition("crate");
  ASSERT_TRUE(fallen.has_value());
  EXPECT_NEAR((*fallen)[0], 1.0, 1e-6);
  EXPECT_NEAR((*fallen)[2], 3.0 - 9.81 * 0.1 * 0.1 / 2, 2e-3);

  const std::string delete_model = "/gazebo/delete_model";
  const ProcessResult deleted = run({ros("rosservice"), "call", delete_model, "{model_name: crate}"}, 60.0);
  ASSERT_EQ(deleted.status, 0) << deleted.err;
  EXPECT_THAT(deleted.out, HasSubstr("success: True"));
  EXPECT_THAT(run({ros("rosservice"), "call", "/gazebo/get_model_state", "{model_name: crate}"}).out,
              HasSubstr("success: False"));
  EXPECT_THAT(run({ros("rosservice"), "call", delete_model, "{model_name: crate}"}).out, HasSubstr("success: False"));
  EXPECT_THAT(runCli({"control", "list", "-N", "/one_DOF_robot"}, run_.scratch()).out, HasSubstr("( running )"));
  ASSERT_EQ(run({ros("rosservice"), "call", "/gazebo/unpause_physics"}).status, 0);
}

TEST_F(Ros1BridgeTest, TrajectoryGoalThroughActionlib) {
  // A trajectory controller for the seed's joint, loaded and started through
  // ros_control's services; its action server appears in ROS.
  const fs::path yaml = run_.scratch() / "trajectory.yaml";
  std::ofstream(yaml) << "one_DOF_robot:\n"
                         "  joint1_trajectory_controller:\n"
                         "    type: effort_controllers/JointTrajectoryController\n"
                         "    joints: [joint1]\n"
                         "    gains: {joint1: {p: 100.0, i: 50.0, d: 10.0, i_clamp: 10.0}}\n"
                         "    constraints: {goal_time: 10.0, stopped_velocity_tolerance: 0.05, joint1: {goal: 0.02}}\n";
  ASSERT_EQ(runCli({"param", "load", yaml.string(), "-N", "/one_DOF_robot"}, run_.scratch()).status, 0);
  loadAndStartThroughRos("joint1_trajectory_controller");

  // The result: SUCCEEDED (status 3), error_code 0 (the controller found
  // the joint within the 0.02 rad goal tolerance, settling within goal_time),
  // and the joint at the trajectory's end, 0.5 rad.
  const ProcessResult ended = sendGoalAndWaitForResult(
      "/one_DOF_robot/joint1_trajectory_controller/follow_joint_trajectory", "control_msgs/FollowJointTrajectoryActionGoal",
      "{goal_id: {id: 'g1'}, goal: {trajectory: {joint_names: [joint1], points: "
      "[{positions: [0.5], time_from_start: {secs: 2, nsecs: 0}}]}}}");
  ASSERT_FALSE(ended.timed_out);
  EXPECT_THAT(ended.out, HasSubstr("id: \"g1\""));
  EXPECT_THAT(ended.out, HasSubstr("status: 3"));
  EXPECT_THAT(ended.out, HasSubstr("error_code: 0"));
  const auto position = firstPosition(run({ros("rostopic"), "echo", "-n", "1", "/one_DOF_robot/joint_states"}).out);
  ASSERT_TRUE(position.has_value());
  EXPECT_NEAR(*position, 0.5, 0.02);
}

TEST_F(Ros1BridgeTest, GripperGoalThroughActionlibWithRosParameters) {
  // The configuration exists only on the ROS parameter server (rosparam load
  // after the bridge started), as ros_control users keep it: load_controller
  // reads it from there.
  loadGripperParametersIntoRos();
  EXPECT_THAT(runCli({"param", "get", "/one_DOF_robot/joint1_gripper_controller/type"}, run_.scratch()).out,
              Not(HasSubstr("GripperActionController")));

  loadAndStartThroughRos("joint1_gripper_controller");
  EXPECT_THAT(runCli({"param", "get", "/one_DOF_robot/joint1_gripper_controller/gains/joint1/p"}, run_.scratch()).out,
              HasSubstr("500"));

  // SUCCEEDED (3) with reached_goal, not stalled, at the commanded position.
  const ProcessResult ended =
      sendGoalAndWaitForResult("/one_DOF_robot/joint1_gripper_controller/gripper_cmd", "control_msgs/GripperCommandActionGoal",
                               "{goal_id: {id: 'grip'}, goal: {command: {position: 0.3, max_effort: 20.0}}}");
  ASSERT_FALSE(ended.timed_out);
  EXPECT_THAT(ended.out, HasSubstr("id: \"grip\""));
  EXPECT_THAT(ended.out, HasSubstr("status: 3"));
  EXPECT_THAT(ended.out, HasSubstr("reached_goal: True"));
  EXPECT_THAT(ended.out, HasSubstr("stalled: False"));
  std::smatch reported;
  ASSERT_TRUE(std::regex_search(ended.out, reported, std::regex(R"(\n\s+position: ([-+0-9.eE]+))"))) << ended.out;
  EXPECT_NEAR(std::stod(reported[1].str()), 0.3, 0.01) << ended.out;
  const auto position = firstPosition(run({ros("rostopic"), "echo", "-n", "1", "/one_DOF_robot/joint_states"}).out);
  ASSERT_TRUE(position.has_value());
  EXPECT_NEAR(*position, 0.3, 0.01);
}

TEST_F(Ros1BridgeTest, SpawnerCallSequenceLoadsStartsAndTakesDown) {
  // ros_control's spawner, as a launch file runs it in the robot's namespace,
  // after rosparam loaded the configuration: it loads each name (a name
  // without configuration fails and is left out), starts the loaded ones in
  // one STRICT switch, and on Ctrl-C stops and unloads them.
  loadGripperParametersIntoRos();
  ASSERT_THAT(run({ros("rosservice"), "call", "/one_DOF_robot/controller_manager/switch_controller",
                   "{start_controllers: [], stop_controllers: [joint1_position_controller], strictness: 2}"}).out,
              HasSubstr("ok: True"));
  ChildProcess spawner({"/usr/bin/python3", (fs::path(SERVOLOOP_SOURCE_DIR) / "tests/ros1/spawner_calls.py").string(),
                        "--namespace", "/one_DOF_robot", "joint1_gripper_controller", "not_configured"},
                       options("spawner"));
  ASSERT_TRUE(spawner.waitForOutput("started: joint1_gripper_controller", 60.0))
      << spawner.currentOut() << spawner.currentErr();
  EXPECT_THAT(spawner.currentOut(), HasSubstr("failed to load not_configured"));
  EXPECT_THAT(runCli({"control", "list", "-N", "/one_DOF_robot"}, run_.scratch()).out,
              HasSubstr("joint1_gripper_controller - effort_controllers/GripperActionController ( running )"));

  spawner.signal(SIGINT);
  ASSERT_TRUE(spawner.waitForOutput("taken down: joint1_gripper_controller", 30.0)) << spawner.currentErr();
  EXPECT_FALSE(spawner.wait(30.0).timed_out);
  const CliResult list = runCli({"control", "list", "-N", "/one_DOF_robot"}, run_.scratch());
  EXPECT_THAT(list.out, Not(HasSubstr("joint1_gripper_controller")));
  EXPECT_THAT(list.out, HasSubstr("joint_state_controller"));
}

TEST_F(Ros1BridgeTest, RosToolsFindServoloopsMessagesWithNoStepOfTheUsers) {
  // A Python started afresh, with no PYTHONPATH (SetUp removed it), imports
  // the packages Debian lacks, from this build's generated folder, through
  // the .pth file the bridge wrote in the user's site-packages.
  const ProcessResult imported = run({"/usr/bin/python3", "-c",
                                      "import control_msgs.msg, controller_manager_msgs.srv, gazebo_msgs.msg, site; "
                                      "print(controller_manager_msgs.__file__); print(site.getusersitepackages())"});
  ASSERT_EQ(imported.status, 0) << imported.err;
  EXPECT_THAT(imported.out, HasSubstr("share/servoloop/ros1/python/controller_manager_msgs"));
  EXPECT_THAT(imported.out, HasSubstr((run_.scratch() / "home").string()));
  // And rostopic reads a controller's control_msgs state.
  const ProcessResult state = run({ros("rostopic"), "echo", "-n", "1", "/one_DOF_robot/joint1_position_controller/state"});
  EXPECT_EQ(state.status, 0) << state.err;
  EXPECT_THAT(state.out, HasSubstr("process_value:"));
}

TEST_F(Ros1BridgeTest, AnUnloadedControllersTopicsLeaveTheMasterAndComeBackWithIt) {
  const std::string state = "/one_DOF_robot/joint1_position_controller/state";
  auto listed = [&](const std::string& topic) {
    const std::string topics = run({ros("rostopic"), "list"}).out + "\n";
    return topics.find(topic + "\n") != std::string::npos;
  };
  ASSERT_TRUE(waitUntil([&] { return listed(state) && listed(kCommandTopic); }, 30.0));
  const std::string manager = "/one_DOF_robot/controller_manager/";
  ASSERT_THAT(run({ros("rosservice"), "call", manager + "switch_controller",
                   "{start_controllers: [], stop_controllers: [joint1_position_controller], strictness: 2}"}).out,
              HasSubstr("ok: True"));
  ASSERT_THAT(run({ros("rosservice"), "call", manager + "unload_controller", "name: joint1_position_controller"}).out,
              HasSubstr("ok: True"));
  // Nothing in the node publishes the state or reads the command now: both
  // are off the master, as ros_control's would be.
  EXPECT_TRUE(waitUntil([&] { return !listed(state) && !listed(kCommandTopic); }, 30.0))
      << run({ros("rostopic"), "list"}).out;
  EXPECT_TRUE(listed("/one_DOF_robot/joint_states"));
  // Loaded and started again, they come back.
  ASSERT_THAT(run({ros("rosservice"), "call", manager + "load_controller", "name: joint1_position_controller"}).out,
              HasSubstr("ok: True"));
  ASSERT_THAT(run({ros("rosservice"), "call", manager + "switch_controller",
                   "{start_controllers: [joint1_position_controller], stop_controllers: [], strictness: 2}"}).out,
              HasSubstr("ok: True"));
  EXPECT_TRUE(waitUntil([&] { return listed(state) && listed(kCommandTopic); }, 30.0))
      << run({ros("rostopic"), "list"}).out;
  const ProcessResult echo = run({ros("rostopic"), "echo", "-n", "1", state});
  EXPECT_THAT(echo.out, HasSubstr("process_value:"));
}

// ros_control's dynamic_reconfigure of a PID, driven by Debian's dynparam:
// listed, the seed's gains as its YAML gives them, a change the running
// controller takes at once (its state topic reports the gains its updates
// use), a value past control_toolbox's range clamped to it, and the parameter
// server following, as a dynamic_reconfigure server does.
TEST_F(Ros1BridgeTest, DynparamChangesARunningControllersPidGains) {
  const std::string pid = "/one_DOF_robot/joint1_position_controller/pid";
  const auto dynparam = [&](std::vector<std::string> args) {
    args.insert(args.begin(), {"/usr/bin/python3", ros_lib("dynamic_reconfigure/dynparam")});
    return run(args, 60.0);
  };
  ASSERT_TRUE(waitUntil([&] { return (dynparam({"list"}).out + "\n").find(pid + "\n") != std::string::npos; }, 30.0))
      << dynparam({"list"}).err;
  const ProcessResult got = dynparam({"get", pid});
  ASSERT_EQ(got.status, 0) << got.err;
  for (const char* expected : {"'p': 10.0", "'i': 10.0", "'d': 10.0", "'i_clamp_min': -10.0", "'i_clamp_max': 10.0",
                               "'antiwindup': False"}) {
    EXPECT_THAT(got.out, HasSubstr(expected));
  }

  const ProcessResult set = dynparam({"set", pid, "{'p': 42.5, 'd': 0.5, 'i_clamp_max': 5000.0}"});
  ASSERT_EQ(set.status, 0) << set.err;
  const std::string state = "/one_DOF_robot/joint1_position_controller/state";
  EXPECT_TRUE(waitUntil([&] {
    const std::string echo = run({ros("rostopic"), "echo", "-n", "1", state}).out;
    return numberField(echo, "p") == 42.5 && numberField(echo, "d") == 0.5 && numberField(echo, "i") == 10.0;
  }, 30.0));
  const ProcessResult after = dynparam({"get", pid});
  EXPECT_THAT(after.out, HasSubstr("'p': 42.5"));
  EXPECT_THAT(after.out, HasSubstr("'i_clamp_max': 1000.0"));  // the range's end
  EXPECT_THAT(run({ros("rosparam"), "get", pid + "/p"}).out, HasSubstr("42.5"));
  const CliResult node_gains = runCli({"control", "gains", "joint1_position_controller", "--json", "-N",
                                       "/one_DOF_robot"}, run_.scratch());
  ASSERT_EQ(node_gains.status, 0) << node_gains.err;
  EXPECT_EQ(nlohmann::json::parse(node_gains.out)[0]["i_clamp_max"], 1000.0);
  // A gain changed on servoloop's side reaches ROS's parameter_updates.
  ASSERT_EQ(runCli({"control", "gains", "joint1_position_controller", "--i", "3", "-N", "/one_DOF_robot"},
                   run_.scratch()).status, 0);
  EXPECT_TRUE(waitUntil([&] { return dynparam({"get", pid}).out.find("'i': 3.0") != std::string::npos; }, 30.0));
}

TEST_F(Ros1BridgeTest, TheBridgeEndsPromptlyOnCtrlC) {
  ASSERT_TRUE(bridge_.has_value());
  const auto start = std::chrono::steady_clock::now();
  bridge_->signal(SIGINT);
  const ProcessResult ended = bridge_->wait(20.0);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  bridge_.reset();
  EXPECT_EQ(ended.status, 0) << ended.err;
  // Within half a second of Ctrl-C (the run's figure is in the log).
  std::printf("the bridge ended %.3f s after SIGINT\n", seconds);
  EXPECT_LT(seconds, 0.5);
  EXPECT_TRUE(nodeAnswers());
}

TEST_F(Ros1BridgeTest, NeitherRoscoreNorTheBridgeEndingStopsTheNode) {
  // A NaN command from ROS is refused by the node; the bridge goes on.
  run({ros("rostopic"), "pub", "-1", kCommandTopic, "std_msgs/Float64", "--", ".nan"});
  EXPECT_TRUE(waitUntil([&] { return bridge_->currentErr().find("a command must be a finite number") != std::string::npos ||
                                     bridge_->currentOut().find("a command must be a finite number") != std::string::npos; },
                        20.0));

  roscore_->signal(SIGINT);  // roscore ends its master and rosout, then itself
  ASSERT_FALSE(roscore_->wait(20.0).timed_out);
  ::kill(-roscore_->pid(), SIGKILL);
  roscore_.reset();
  EXPECT_TRUE(nodeAnswers());

  bridge_->signal(SIGKILL);
  bridge_->wait(10.0);
  bridge_.reset();
  EXPECT_TRUE(nodeAnswers());
  const CliResult safety = runCli({"control", "safety", "-N", "/one_DOF_robot"}, run_.scratch());
  EXPECT_THAT(safety.out, HasSubstr("running"));
}

class Ros1BridgeFromLaunchTest : public Ros1BridgeTest {
 protected:
  bool bridgeFromLaunch() const override { return true; }
};

TEST_F(Ros1BridgeFromLaunchTest, LaunchStartsAndStopsTheBridge) {
  const ProcessResult echo = run({ros("rostopic"), "echo", "-n", "1", "/one_DOF_robot/joint_states"});
  ASSERT_EQ(echo.status, 0) << echo.err;
  EXPECT_THAT(echo.out, HasSubstr("- joint1"));
  EXPECT_THAT(run({ros("rosnode"), "list"}).out, HasSubstr("/servoloop_bridge_one_DOF_robot"));

  // Ctrl-C on the node ends its bridge first: the bridge leaves the ROS graph.
  node_->signal(SIGINT);
  ASSERT_FALSE(node_->wait(30.0).timed_out);
  node_.reset();
  EXPECT_TRUE(waitUntil([&] {
    return run({ros("rosnode"), "list"}).out.find("servoloop_bridge") == std::string::npos;
  }, 20.0));
}

// The seed's first robot (continuous joint, no transmission) with joint states
// and an effort controller, as robots/one_dof/one_dof_ros1_gazebo.launch.yaml
// sets it up for the tutorial's ROS node; at --rtf 0.5, so that the node's
// 100 Hz loop of two service calls (a few wall milliseconds each on a loaded
// 2-core machine) stays well inside its 10 ms of simulated time.
class Ros1GazeboServicesTest : public Ros1BridgeTest {
 protected:
  std::string launchFile() const override { return "one_dof_ros1_gazebo.launch.yaml"; }
  std::string realTimeFactor() const override { return "0.5"; }

  // The joint's effort within 1e-9 of `expected` (it crosses JSON and ROS
  // exactly, but is a sum of doubles).
  bool effortIs(double expected) {
    const auto effort = jointEffort();
    return effort && std::abs(*effort - expected) < 1e-9;
  }

  std::optional<double> jointEffort() {
    static const std::regex pattern(R"(effort: \[([-+0-9.eE]+))");
    const std::string echo = run({ros("rostopic"), "echo", "-n", "1", "/one_DOF_robot/joint_states"}).out;
    std::smatch match;
    if (!std::regex_search(echo, match, pattern)) return std::nullopt;
    return std::stod(match[1].str());
  }
};

TEST_F(Ros1GazeboServicesTest, ServicesAnswerAsGazebosDo) {
  const ProcessResult properties = run({ros("rosservice"), "call", "/gazebo/get_joint_properties", "joint_name: joint1"});
  ASSERT_EQ(properties.status, 0) << properties.err;
  EXPECT_THAT(properties.out, HasSubstr("type: 1"));  // CONTINUOUS, as the URDF says
  EXPECT_THAT(properties.out, HasSubstr("success: True"));
  EXPECT_THAT(run({ros("rosservice"), "call", "/gazebo/get_joint_properties", "joint_name: elbow"}).out,
              HasSubstr("success: False"));
  const ProcessResult model = run({ros("rosservice"), "call", "/gazebo/get_model_state", "{model_name: one_DOF_robot}"});
  EXPECT_THAT(model.out, HasSubstr("success: True"));
  EXPECT_THAT(model.out, HasSubstr("w: 1.0"));  // spawned with no pose: the world's origin, unrotated
  EXPECT_THAT(run({ros("rosservice"), "call", "/gazebo/get_model_state", "{model_name: two_joint_arm}"}).out,
              HasSubstr("success: False"));

  // Efforts add up over their windows of simulated time: 2.0 N·m without
  // end, then 0.5 N·m more for 5 s (10 s of wall time: each look with
  // rostopic echo takes a second or more); the joint's effort (what the effort
  // controller commands) is 2.5 during the window and 2.0 after it.
  const std::string apply = "/gazebo/apply_joint_effort";
  EXPECT_THAT(run({ros("rosservice"), "call", apply, "{joint_name: joint1, effort: 2.0, duration: {secs: -1, nsecs: 0}}"}).out,
              HasSubstr("success: True"));
  EXPECT_TRUE(waitUntil([&] { return effortIs(2.0); }, 20.0)) << jointEffort().value_or(-1);
  EXPECT_THAT(run({ros("rosservice"), "call", apply, "{joint_name: joint1, effort: 0.5, duration: {secs: 5, nsecs: 0}}"}).out,
              HasSubstr("success: True"));
  EXPECT_TRUE(waitUntil([&] { return effortIs(2.5); }, 8.0)) << jointEffort().value_or(-1);
  EXPECT_TRUE(waitUntil([&] { return effortIs(2.0); }, 30.0)) << jointEffort().value_or(-1);
  EXPECT_THAT(run({ros("rosservice"), "call", apply, "{joint_name: elbow, effort: 1.0, duration: {secs: 1, nsecs: 0}}"}).out,
              HasSubstr("success: False"));
}

TEST_F(Ros1GazeboServicesTest, TheSeedsOwnNodeHoldsTheJoint) {
  // The tutorial's node, built from its text, and its own command.
  ChildProcess seed({std::string(SERVOLOOP_SEED_NODE)}, options("seed_node"));
  ASSERT_TRUE(waitUntil([&] { return run({ros("rosnode"), "list"}).out.find("/minimal_joint_controller") != std::string::npos; },
                        30.0));
  ChildProcess command({ros("rostopic"), "pub", "-r", "10", "/pos_cmd", "std_msgs/Float64", "1.0"}, options("pos_cmd"));

  // Its PD law Kp (q_cmd - q) - Kv q' holds the arm where it balances gravity
  // on link2 (1 kg, centre 0.5 m from the joint): 10 (1 - q) + 1 · 9.81 · 0.5
  // · sin q = 0 at q* = 1.4888 rad (the P term alone, so not at the command:
  // the tutorial's controller has no integral term). Each 10 ms effort of the
  // node's 100 Hz calls meets the next with a few milliseconds of overlap or
  // gap, as Gazebo's windows do, so the arm settles near q*: within 0.06 rad.
  double q_star = 1.0;
  for (double lo = 1.0, hi = 2.0; hi - lo > 1e-9;) {
    q_star = (lo + hi) / 2;
    (10.0 * (1.0 - q_star) + 9.81 * 0.5 * std::sin(q_star) > 0.0 ? lo : hi) = q_star;
  }
  std::vector<double> recent;
  EXPECT_TRUE(waitUntil([&] {
    const auto q = firstPosition(run({ros("rostopic"), "echo", "-n", "1", "/one_DOF_robot/joint_states"}).out);
    if (!q) return false;
    recent.push_back(*q);
    if (recent.size() > 5) recent.erase(recent.begin());
    const auto [low, high] = std::minmax_element(recent.begin(), recent.end());
    return recent.size() == 5 && *high - *low < 0.02 && std::abs(*q - q_star) < 0.06;
  }, 90.0)) << "q* = " << q_star << ", last positions " << ::testing::PrintToString(recent);
  // The node republishes what it read from the services: jnt_pos is joint1.
  const auto jnt_pos = numberField("\n" + run({ros("rostopic"), "echo", "-n", "1", "/jnt_pos"}).out, "data");
  ASSERT_TRUE(jnt_pos.has_value());
  EXPECT_NEAR(*jnt_pos, q_star, 0.06);
  command.signal(SIGINT);
  seed.signal(SIGINT);
}

}  // namespace
}  // namespace servoloop::cli::testing
