// ROS 1's own tools against a servoloop node through `servoloop ros1-bridge`:
// a private roscore on a free port, the seed robot simulated on bullet, then
// rostopic, rosservice, rosparam and rosbag as a ROS user types them.
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
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
    // from where `servoloop ros1-bridge --print-env` points.
    const ProcessResult env = run({SERVOLOOP_CLI_EXE, "ros1-bridge", "--print-env"});
    std::smatch match;
    ASSERT_TRUE(std::regex_search(env.out, match, std::regex("PYTHONPATH=\"([^\"$]+)"))) << env.out;
    setenv("PYTHONPATH", match[1].str().c_str(), 1);

    roscore_.emplace(std::vector<std::string>{ros("roscore"), "-p", std::to_string(port)}, options("roscore"));
    ASSERT_TRUE(waitUntil([&] { return run({ros("rosparam"), "get", "/rosdistro"}).status == 0; }, 60.0))
        << roscore_->currentOut() << roscore_->currentErr();

    node_.emplace(std::vector<std::string>{"launch", (kOneDof / "one_dof_w_jnt_ctl.launch.yaml").string(), "--rtf", "5"},
                  run_.scratch());
    ASSERT_TRUE(waitUntil([&] {
      const CliResult list = runCli({"control", "list", "-N", "/one_DOF_robot"}, run_.scratch());
      return list.status == 0 && list.out.find("( running )") != std::string::npos;
    }, 60.0)) << node_->currentErr();

    startBridge();
  }

  void TearDown() override {
    // roscore is a launcher: SIGINT lets it stop the master and rosout it started.
    for (ChildProcess* child : {static_cast<ChildProcess*>(bridge_ ? &*bridge_ : nullptr),
                                static_cast<ChildProcess*>(node_ ? &*node_ : nullptr),
                                roscore_ ? &*roscore_ : nullptr}) {
      if (child == nullptr) continue;
      child->signal(SIGINT);
      child->wait(20.0);
    }
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
  double last = 0.0;
  EXPECT_TRUE(waitUntil([&] {
    const auto position = firstPosition(run({ros("rostopic"), "echo", "-n", "1", "/one_DOF_robot/joint_states"}).out);
    if (position) last = *position;
    return position && std::abs(*position - 1.0) < 0.01;
  }, 120.0)) << "joint1 at " << last;
  pub.signal(SIGINT);

  // rosbag: 5 s of simulated time hold 5 s × 50 Hz (joint_state_controller's
  // publish_rate) joint states. rosbag ends the window by /clock, which the
  // bridge publishes every 5 ms of wall time (25 ms of simulated time at
  // --rtf 5), so the count may be off by that much at either end; inside the
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
  EXPECT_GE(stamps_ns.size(), 248u);
  EXPECT_LE(stamps_ns.size(), 252u);
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

TEST_F(Ros1BridgeTest, NeitherRoscoreNorTheBridgeEndingStopsTheNode) {
  // A NaN command from ROS is refused by the node; the bridge goes on.
  run({ros("rostopic"), "pub", "-1", kCommandTopic, "std_msgs/Float64", "--", ".nan"});
  EXPECT_TRUE(waitUntil([&] { return bridge_->currentErr().find("a command must be a finite number") != std::string::npos ||
                                     bridge_->currentOut().find("a command must be a finite number") != std::string::npos; },
                        20.0));

  roscore_->signal(SIGINT);  // roscore ends its master and rosout, then itself
  ASSERT_FALSE(roscore_->wait(20.0).timed_out);
  roscore_.reset();
  EXPECT_TRUE(nodeAnswers());

  bridge_->signal(SIGKILL);
  bridge_->wait(10.0);
  bridge_.reset();
  EXPECT_TRUE(nodeAnswers());
  const CliResult safety = runCli({"control", "safety", "-N", "/one_DOF_robot"}, run_.scratch());
  EXPECT_THAT(safety.out, HasSubstr("running"));
}

}  // namespace
}  // namespace servoloop::cli::testing
