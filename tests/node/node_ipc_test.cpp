// The operations of docs/node_operations.md against a running node (the seed
// robot on the mock backend), through the real socket and IpcClient.
#include <gtest/gtest.h>

#include <stdlib.h>

#include <chrono>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "node_test_support.hpp"
#include "servoloop/ipc/ipc_client.hpp"
#include "servoloop/ipc/ipc_socket_path.hpp"
#include "servoloop/node/node.hpp"
#include "servoloop/core/errors.hpp"

namespace {

using namespace servoloop::controller_manager;
using namespace servoloop::node;
using namespace servoloop::node_test;
using nlohmann::json;

constexpr const char* kNamespace = "/one_DOF_robot";

class NodeIpc : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(backendAvailable("mock"));
    ::setenv("SERVOLOOP_RUN_DIR", run_dir_.path().c_str(), 1);
    NodeOptions options;
    options.real_time_factor = 4.0;  // no duration: runs until shut down
    node_ = std::make_unique<Node>(seedLaunch("mock"), options);
    node_->start();
    ASSERT_TRUE(servoloop::ipc::waitForNode(kNamespace, 5.0));
    client_ = servoloop::ipc::IpcClient::connectToNode(kNamespace);
  }
  void TearDown() override {
    client_.close();
    node_.reset();
    ::unsetenv("SERVOLOOP_RUN_DIR");
  }

  json call(const std::string& op, const json& args = json::object()) { return client_.call(op, args); }
  std::string errorOf(const std::string& op, const json& args = json::object()) {
    json request = args;
    request["op"] = op;
    const json reply = client_.request(request);
    EXPECT_FALSE(reply.value("ok", true)) << reply.dump();
    return reply.value("error", "");
  }

  TempDir run_dir_{"servoloop-node-ipc"};
  std::unique_ptr<Node> node_;
  servoloop::ipc::IpcClient client_;
};

TEST_F(NodeIpc, PingNamesTheRobot) {
  const json reply = call("ping");
  EXPECT_EQ(reply["namespace"], kNamespace);
  EXPECT_EQ(reply["robots"], json::array({kNamespace}));
  EXPECT_GE(reply["sim_time"].get<double>(), 0.0);
}

TEST_F(NodeIpc, ControlListShowsBothControllersRunningWithTheirClaims) {
  const json controllers = call("control.list")["controllers"];
  ASSERT_EQ(controllers.size(), 2u) << controllers.dump();
  EXPECT_EQ(controllers[0]["name"], "joint_state_controller");
  EXPECT_EQ(controllers[0]["type"], "joint_state_controller/JointStateController");
  EXPECT_EQ(controllers[0]["state"], "running");
  EXPECT_EQ(controllers[1]["name"], "joint1_position_controller");
  EXPECT_EQ(controllers[1]["state"], "running");
  bool claims_joint1 = false;
  for (const json& claim : controllers[1]["claimed_resources"]) {
    claims_joint1 |= claim["hardware_interface"] == "EffortJointInterface" && claim["resources"] == json::array({"joint1"});
  }
  EXPECT_TRUE(claims_joint1) << controllers[1].dump();
  // The joint state controller claims nothing (reading needs no claim).
  for (const json& claim : controllers[0]["claimed_resources"]) EXPECT_TRUE(claim["resources"].empty());
}

TEST_F(NodeIpc, ListTypesAndJoints) {
  bool has_pid_controller = false;
  const json types = call("control.list_types")["types"];
  for (const json& type : types) {
    has_pid_controller |= type["type"] == "effort_controllers/JointPositionController" && type["kind"] == "controller";
  }
  EXPECT_TRUE(has_pid_controller);
  const json joints = call("control.list_joints")["joints"];
  ASSERT_EQ(joints.size(), 1u);
  EXPECT_EQ(joints[0]["name"], "joint1");
  EXPECT_EQ(joints[0]["interfaces"][0], "JointStateInterface");
  EXPECT_NE(joints[0]["interfaces"].dump().find("EffortJointInterface"), std::string::npos);
}

TEST_F(NodeIpc, ParametersFromTheSeedYaml) {
  EXPECT_EQ(call("param.get", {{"name", "/one_DOF_robot/joint1_position_controller/pid/p"}})["value"], 10.0);
  EXPECT_EQ(call("param.get", {{"name", "/one_DOF_robot/joint_state_controller/publish_rate"}})["value"], 50);
  // The world's physics step is where the backend reads it.
  EXPECT_EQ(call("param.get", {{"name", "/one_DOF_robot/sim/time_step"}})["value"], 0.001);
  call("param.set", {{"name", "/one_DOF_robot/extra/gain"}, {"value", "2.5"}});
  EXPECT_EQ(call("param.get", {{"name", "/one_DOF_robot/extra/gain"}})["value"], 2.5);
  call("param.set", {{"name", "/one_DOF_robot/extra/list"}, {"value", json::array({1, 2})}});
  EXPECT_EQ(call("param.get", {{"name", "/one_DOF_robot/extra/list"}})["value"], json::array({1, 2}));
  const json names = call("param.list", {{"namespace", "/one_DOF_robot/extra"}})["names"];
  EXPECT_EQ(names, json::array({"/one_DOF_robot/extra/gain", "/one_DOF_robot/extra/list"}));
  call("param.load", {{"yaml", "added: {x: 1}"}, {"source", "inline"}, {"namespace", "/one_DOF_robot"}});
  EXPECT_EQ(call("param.get", {{"name", "/one_DOF_robot/added/x"}})["value"], 1);
  EXPECT_NE(call("param.dump", {{"namespace", "/one_DOF_robot/added"}})["yaml"].get<std::string>().find("x: 1"),
            std::string::npos);
  EXPECT_NE(errorOf("param.get", {{"name", "/one_DOF_robot/nothing"}}).find("nothing"), std::string::npos);
}

TEST_F(NodeIpc, TopicPubMovesTheJointAndSubscribeStreamsJointStates) {
  const json topics = call("topic.list")["topics"];
  EXPECT_NE(topics.dump().find("/one_DOF_robot/joint_states"), std::string::npos);

  call("topic.subscribe", {{"topic", "/one_DOF_robot/joint_states"}});
  call("topic.pub", {{"topic", "/one_DOF_robot/joint1_position_controller/command"},
                     {"type", "std_msgs/Float64"},
                     {"msg", {{"data", 0.5}}}});
  // At 4x real time the joint reaches 0.4 rad within a few wall seconds.
  double position = 0.0;
  int messages = 0;
  double last_stamp = -1.0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(15);
  while (position < 0.4 && std::chrono::steady_clock::now() < deadline) {
    const auto message = client_.readStream(1.0);
    if (!message) continue;
    ASSERT_EQ((*message)["stream"], "/one_DOF_robot/joint_states");
    EXPECT_EQ((*message)["type"], "sensor_msgs/JointState");
    const double stamp = (*message)["stamp"].get<double>();
    EXPECT_GT(stamp, last_stamp);
    last_stamp = stamp;
    position = (*message)["msg"]["position"][0].get<double>();
    ++messages;
  }
  EXPECT_GE(position, 0.4) << "after " << messages << " joint state messages";
  call("topic.unsubscribe", {{"topic", "/one_DOF_robot/joint_states"}});
  EXPECT_NE(errorOf("topic.unsubscribe", {{"topic", "/one_DOF_robot/joint_states"}}).find("not subscribed"),
            std::string::npos);
}

TEST_F(NodeIpc, SwitchStopsAndStartsAController) {
  call("control.switch", {{"stop", {"joint1_position_controller"}}, {"strictness", "strict"}});
  EXPECT_EQ(call("control.list")["controllers"][1]["state"], "stopped");
  call("control.unload", {{"name", "joint1_position_controller"}});
  EXPECT_EQ(call("control.list")["controllers"].size(), 1u);
  call("control.load", {{"name", "joint1_position_controller"}});
  call("control.switch", {{"start", {"joint1_position_controller"}}, {"strictness", "best_effort"}});
  EXPECT_EQ(call("control.list")["controllers"][1]["state"], "running");
}

// A client publishing to ever new names is stopped at the topic limit; topics
// that exist still take messages.
TEST_F(NodeIpc, TopicPubToNewNamesStopsAtTheLimit) {
  const std::size_t existing = call("topic.list")["topics"].size();
  std::size_t created = 0;
  std::string error;
  for (std::size_t i = 0; i < 5000 && error.empty(); ++i) {
    json request = {{"op", "topic.pub"}, {"topic", "/spam/t" + std::to_string(i)}, {"type", "std_msgs/Float64"},
                    {"msg", {{"data", 1.0}}}};
    const json reply = client_.request(request);
    if (reply.value("ok", false)) {
      ++created;
    } else {
      error = reply.value("error", "");
    }
  }
  EXPECT_EQ(existing + created, 4096u);
  EXPECT_NE(error.find("would be topic number 4097 of this robot; the limit is 4096"), std::string::npos) << error;
  call("topic.pub", {{"topic", "/spam/t0"}, {"msg", {{"data", 2.0}}}});
  EXPECT_EQ(call("ping")["namespace"], kNamespace);
}

TEST_F(NodeIpc, BadRequestsGetErrorsAndTheNodeKeepsServing) {
  EXPECT_NE(errorOf("control.fly").find("unknown op 'control.fly'"), std::string::npos);
  EXPECT_NE(errorOf("control.load", {{"name", "joint9_controller"}}).find("joint9_controller"), std::string::npos);
  EXPECT_NE(errorOf("control.load").find("'name'"), std::string::npos);
  EXPECT_NE(errorOf("control.switch", {{"start", {"x"}}, {"strictness", "sometimes"}}).find("strictness"),
            std::string::npos);
  EXPECT_NE(errorOf("topic.pub", {{"topic", "/one_DOF_robot/joint1_position_controller/command"},
                                  {"msg", {{"data", "high"}}}})
                .find("data"),
            std::string::npos);
  EXPECT_NE(errorOf("model.spawn", {{"urdf", "relative.urdf"}}).find("absolute"), std::string::npos);
  // Still alive and running.
  EXPECT_EQ(call("ping")["namespace"], kNamespace);
  EXPECT_EQ(call("control.list")["controllers"][1]["state"], "running");
}

TEST_F(NodeIpc, WorldShutdownEndsTheRun) {
  call("world.shutdown");
  node_->waitUntilDone();  // returns at once: the shutdown was requested
  EXPECT_TRUE(node_->shutdownRequested());
  node_->shutdown();
  EXPECT_FALSE(fs::exists(servoloop::ipc::socketPathFor(kNamespace)));
}

TEST(NodeIpcWorld, EmptyWorldServesDefaultSocketAndSpawnsAModel) {
  ASSERT_TRUE(backendAvailable("mock"));
  TempDir run_dir("servoloop-node-world");
  ::setenv("SERVOLOOP_RUN_DIR", run_dir.path().c_str(), 1);
  {
    LaunchFile launch;
    launch.world.backend = "mock";
    NodeOptions options;
    Node node(launch, options);
    node.start();
    ASSERT_TRUE(servoloop::ipc::waitForNode("/", 5.0));
    servoloop::ipc::IpcClient world = servoloop::ipc::IpcClient::connectToNode("/");
    EXPECT_EQ(world.call("ping")["robots"], json::array());
    const json reply =
        world.call("model.spawn", {{"urdf", (oneDofDir() / "minimal_robot_description_w_jnt_ctl.urdf").string()},
                                   {"model", "one_DOF_robot"},
                                   {"params", {(oneDofDir() / "control_config" / "one_dof_ctl_params.yaml").string()}}},
                   20.0);
    EXPECT_EQ(reply["namespace"], kNamespace);
    ASSERT_TRUE(servoloop::ipc::waitForNode(kNamespace, 5.0));
    servoloop::ipc::IpcClient robot = servoloop::ipc::IpcClient::connectToNode(kNamespace);
    robot.call("control.load", {{"name", "joint_state_controller"}});
    robot.call("control.switch", {{"start", {"joint_state_controller"}}});
    EXPECT_EQ(robot.call("control.list")["controllers"][0]["state"], "running");
    // The world socket acts on the only robot.
    EXPECT_EQ(world.call("control.list")["controllers"].size(), 1u);
    node.shutdown();
  }
  ::unsetenv("SERVOLOOP_RUN_DIR");
}

}  // namespace
