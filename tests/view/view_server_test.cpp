// The view's server (view/view_server.hpp) against a running node (the seed
// robot on the mock backend) through the node's real sockets, with
// WebSocket clients standing in for pages: what a page is sent (the scene
// read back against the seed's URDF, frames that follow the world),
// read-only and control modes, 20 pages at once and pages dropped
// mid-transfer, files outside the served folders, and a port in use.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <stdlib.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "node_test_support.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/ipc/ipc_client.hpp"
#include "servoloop/node/node.hpp"
#include "servoloop/view/view_server.hpp"
#include "static_files.hpp"
#include "wait_until.hpp"
#include "ws_test_client.hpp"

namespace {

using namespace servoloop;
using namespace servoloop::node_test;
using nlohmann::json;
using servoloop::testing::nextOfType;
using servoloop::testing::WsTestClient;
namespace fs = std::filesystem;

constexpr const char* kRobot = "/one_DOF_robot";

view::NodeRequest overSocket(const std::string& node_name) {
  auto client = std::make_shared<ipc::IpcClient>(ipc::IpcClient::connectToNode(node_name));
  return [client](const json& request) { return client->request(request, 30.0); };
}

class ViewServerTest : public ::testing::Test {
 protected:
  void startNode(const node::LaunchFile& launch) {
    ASSERT_TRUE(backendAvailable("mock"));
    ::setenv("SERVOLOOP_RUN_DIR", run_dir_.path().c_str(), 1);
    node::NodeOptions options;
    options.real_time_factor = 1.0;
    node_ = std::make_unique<node::Node>(launch, options);
    node_->start();
    ASSERT_TRUE(ipc::waitForNode("/", 5.0));
  }
  void startView(bool control) {
    view::ViewOptions options;
    options.port = 0;
    options.control = control;
    view_ = std::make_unique<view::ViewServer>(options, [] { return overSocket("/"); });
    view_->start();
    url_ = "ws://127.0.0.1:" + std::to_string(view_->port()) + "/ws";
  }
  void TearDown() override {
    view_.reset();
    node_.reset();
    ::unsetenv("SERVOLOOP_RUN_DIR");
  }

  TempDir run_dir_{"servoloop-view-run"};
  std::unique_ptr<node::Node> node_;
  std::unique_ptr<view::ViewServer> view_;
  std::string url_;
};

TEST(ViewAddress, TakesPortHostAndPortAndRefusesTheRest) {
  view::ViewOptions options;
  view::parseViewAddress("9000", options);
  EXPECT_EQ(options.host, "127.0.0.1");
  EXPECT_EQ(options.port, 9000u);
  view::parseViewAddress("0.0.0.0:8081", options);
  EXPECT_EQ(options.host, "0.0.0.0");
  EXPECT_EQ(options.port, 8081u);
  view::parseViewAddress("localhost:7000", options);
  EXPECT_EQ(options.host, "127.0.0.1");
  for (const char* bad : {"", "http", "1:2:x", "70000", "12a", ":-1"}) {
    view::ViewOptions unchanged;
    EXPECT_THROW(view::parseViewAddress(bad, unchanged), ConfigError) << bad;
  }
}

TEST(ViewPort, APortInUseIsOneErrorNamingThePortAndTheFix) {
  const int taken = ::socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(taken, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(taken, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  ASSERT_EQ(::listen(taken, 1), 0);
  socklen_t length = sizeof address;
  ::getsockname(taken, reinterpret_cast<sockaddr*>(&address), &length);
  const unsigned port = ntohs(address.sin_port);

  view::ViewOptions options;
  options.port = port;
  view::ViewServer server(options, [] { return view::NodeRequest(); });
  try {
    server.start();
    ADD_FAILURE() << "a port in use was accepted";
  } catch (const ConfigError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("port " + std::to_string(port)), std::string::npos) << message;
    EXPECT_NE(message.find("in use"), std::string::npos) << message;
    EXPECT_NE(message.find("--view"), std::string::npos) << message;
  }
  ::close(taken);
}

TEST(ViewFiles, FilesOutsideTheServedFoldersAreRefused) {
  TempDir dir("servoloop-view-files");
  const fs::path package = dir.path() / "my_robot";
  fs::create_directories(package / "meshes");
  servoloop::testing::writeFile(package / "package.xml", "<package><name>my_robot</name></package>");
  servoloop::testing::writeFile(package / "meshes" / "arm.stl", "solid arm\nendsolid arm\n");
  servoloop::testing::writeFile(dir.path() / "secret.txt", "not for the page");
  fs::create_symlink(dir.path() / "secret.txt", package / "meshes" / "link_out.stl");

  view::ViewOptions options;
  options.port = 0;
  view::ViewServer server(options, [] { return view::NodeRequest(); });
  server.start();
  const unsigned port = server.port();

  // The page and Debian's three.js are served.
  const auto page = servoloop::testing::httpGet("127.0.0.1", port, "/");
  EXPECT_EQ(page.status, 200);
  EXPECT_NE(page.body.find("three.min.js"), std::string::npos);
  EXPECT_EQ(page.content_type.rfind("text/html", 0), 0u) << page.content_type;
  const auto three = servoloop::testing::httpGet("127.0.0.1", port, "/three/build/three.min.js");
  EXPECT_EQ(three.status, 200);
  EXPECT_GT(three.body.size(), 100000u);

  // Outside: "..", percent-encoded "..", absolute paths, a link out.
  for (const char* path : {"/../../../../etc/passwd", "/three/../../../../etc/passwd", "/%2e%2e/%2e%2e/%2e%2e/etc/passwd",
                           "/three/%2E%2E/%2E%2E/%2E%2E/%2E%2E/etc/passwd", "//etc/passwd", "/three//etc/passwd"}) {
    const auto reply = servoloop::testing::httpGet("127.0.0.1", port, path);
    EXPECT_TRUE(reply.status == 403 || reply.status == 404) << path << ": " << reply.status;
    EXPECT_EQ(reply.body.find("root:"), std::string::npos) << path;
  }

  // A mesh's package is served; a link inside it leading out is not.
  view::StaticFiles files;
  const std::string url = files.meshUrl(package / "meshes" / "arm.stl");
  EXPECT_EQ(url, "/files/0/meshes/arm.stl");
  EXPECT_EQ(files.get(url).status, 200);
  EXPECT_EQ(files.get(url).body, "solid arm\nendsolid arm\n");
  EXPECT_EQ(files.get("/files/0/meshes/link_out.stl").status, 403);
  EXPECT_EQ(files.get("/files/0/../secret.txt").status, 403);
  EXPECT_EQ(files.get("/files/0/../../" + dir.path().filename().string() + "/secret.txt").status, 403);
  EXPECT_EQ(files.get("/files/1/anything").status, 404);
  EXPECT_TRUE(files.meshUrl(package / "meshes" / "missing.stl").empty());
}

TEST_F(ViewServerTest, APageGetsTheSceneOfTheURDFAndFramesThatFollowTheWorld) {
  startNode(seedLaunch("mock"));
  startView(false);
  WsTestClient page;
  ASSERT_TRUE(page.connect(url_)) << page.why();
  const json hello = nextOfType(page, "hello");
  ASSERT_TRUE(hello.is_object());
  EXPECT_FALSE(hello["control"].get<bool>());

  const json scene = nextOfType(page, "scene");
  ASSERT_TRUE(scene.is_object());
  ASSERT_EQ(scene["models"].size(), 1u) << scene.dump();
  const json& model = scene["models"][0];
  EXPECT_EQ(model["ns"], kRobot);
  EXPECT_EQ(model["root"], "world");
  EXPECT_EQ(model["joint_names"], json::array({"joint1"}));
  // The seed's URDF (robots/one_dof/minimal_robot_description_w_jnt_ctl.urdf):
  // joint1 revolute about y, 1 m above link1; link1 a 0.2 x 0.2 x 1 box
  // centred 0.5 m up; link2 a cylinder of radius 0.1 and length 1.
  json joint1, link1, link2;
  for (const json& joint : model["joints"]) {
    if (joint["name"] == "joint1") joint1 = joint;
  }
  for (const json& link : model["links"]) {
    if (link["name"] == "link1") link1 = link;
    if (link["name"] == "link2") link2 = link;
  }
  ASSERT_TRUE(joint1.is_object());
  EXPECT_EQ(joint1["type"], "revolute");
  EXPECT_EQ(joint1["parent"], "link1");
  EXPECT_EQ(joint1["child"], "link2");
  EXPECT_EQ(joint1["axis"], json::array({0.0, 1.0, 0.0}));
  EXPECT_EQ(joint1["origin"]["xyz"], json::array({0.0, 0.0, 1.0}));
  ASSERT_EQ(link1["visuals"].size(), 1u);
  EXPECT_EQ(link1["visuals"][0]["geometry"]["type"], "box");
  EXPECT_EQ(link1["visuals"][0]["geometry"]["size"], json::array({0.2, 0.2, 1.0}));
  EXPECT_EQ(link1["visuals"][0]["origin"]["xyz"], json::array({0.0, 0.0, 0.5}));
  ASSERT_EQ(link1["collisions"].size(), 1u);
  EXPECT_EQ(link1["collisions"][0]["geometry"]["size"], json::array({0.2, 0.2, 0.7}));
  ASSERT_EQ(link2["visuals"].size(), 1u);
  EXPECT_EQ(link2["visuals"][0]["geometry"]["type"], "cylinder");
  EXPECT_DOUBLE_EQ(link2["visuals"][0]["geometry"]["radius"].get<double>(), 0.1);
  EXPECT_DOUBLE_EQ(link2["visuals"][0]["geometry"]["length"].get<double>(), 1.0);

  // Frames: the world's time goes on, and the joint is where the node says.
  const json first = nextOfType(page, "frame");
  ASSERT_TRUE(first.is_object());
  json later;
  ASSERT_TRUE(servoloop::testing::waitUntil(
      [&] {
        later = nextOfType(page, "frame", std::chrono::seconds(2));
        return later.is_object() && later["t"].get<double>() > first["t"].get<double>() + 0.2;
      },
      std::chrono::seconds(20)));
  ASSERT_EQ(later["models"].size(), 1u);
  EXPECT_EQ(later["models"][0]["pose"], json::array({0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0}));  // fixed at the origin
  // Paused, the frame holds the node's own joint state exactly.
  node_->pauseWorld();
  node_->setModelConfiguration(kRobot, {"joint1"}, {0.75});
  json paused;
  ASSERT_TRUE(servoloop::testing::waitUntil(
      [&] {
        paused = nextOfType(page, "frame", std::chrono::seconds(2));
        return paused.is_object() && paused["paused"].get<bool>() &&
               std::abs(paused["models"][0]["q"][0].get<double>() - 0.75) < 1e-12;
      },
      std::chrono::seconds(20)))
      << paused.dump();
  double position = 0.0;
  for (const auto& joint : node_->findRobot(kRobot)->joints()) {
    if (joint.name == "joint1") position = joint.position;
  }
  EXPECT_DOUBLE_EQ(paused["models"][0]["q"][0].get<double>(), position);

  // The controllers of the robot, as control.list gives them.
  const json controllers = nextOfType(page, "controllers");
  ASSERT_TRUE(controllers.is_object());
  ASSERT_EQ(controllers["robots"].size(), 1u);
  std::vector<std::string> names;
  for (const json& controller : controllers["robots"][0]["controllers"]) names.push_back(controller["name"]);
  std::vector<std::string> expected;
  for (const auto& spec : node_->findRobot(kRobot)->manager().listControllers()) expected.push_back(spec.name);
  EXPECT_EQ(names, expected);
}

TEST_F(ViewServerTest, AReadOnlyViewRefusesControlAndAControlViewCarriesItOut) {
  startNode(seedLaunch("mock"));
  startView(false);
  {
    WsTestClient page;
    ASSERT_TRUE(page.connect(url_)) << page.why();
    ASSERT_TRUE(page.send(json{{"op", "estop"}, {"id", 7}, {"ns", kRobot}, {"engaged", true}}.dump()));
    const json reply = nextOfType(page, "reply");
    ASSERT_TRUE(reply.is_object());
    EXPECT_EQ(reply["id"], 7);
    EXPECT_FALSE(reply["ok"].get<bool>());
    EXPECT_NE(reply["error"].get<std::string>().find("--view-control"), std::string::npos);
    EXPECT_FALSE(node_->findRobot(kRobot)->safety().emergencyStopLatched());
  }
  view_.reset();
  startView(true);
  WsTestClient page;
  ASSERT_TRUE(page.connect(url_)) << page.why();
  EXPECT_TRUE(nextOfType(page, "hello")["control"].get<bool>());
  ASSERT_TRUE(page.send(json{{"op", "estop"}, {"id", 1}, {"ns", kRobot}, {"engaged", true}}.dump()));
  json reply = nextOfType(page, "reply");
  EXPECT_TRUE(reply["ok"].get<bool>()) << reply.dump();
  EXPECT_TRUE(node_->findRobot(kRobot)->safety().emergencyStopLatched());
  ASSERT_TRUE(page.send(json{{"op", "estop"}, {"id", 2}, {"ns", kRobot}, {"engaged", false}}.dump()));
  EXPECT_TRUE(nextOfType(page, "reply")["ok"].get<bool>());
  EXPECT_FALSE(node_->findRobot(kRobot)->safety().emergencyStopLatched());

  ASSERT_TRUE(page.send(json{{"op", "switch"}, {"id", 3}, {"ns", kRobot}, {"stop", {"joint1_position_controller"}}}.dump()));
  reply = nextOfType(page, "reply");
  EXPECT_TRUE(reply["ok"].get<bool>()) << reply.dump();
  for (const auto& spec : node_->findRobot(kRobot)->manager().listControllers()) {
    if (spec.name == "joint1_position_controller") {
      EXPECT_NE(spec.state, controller_manager::ControllerState::running);
    }
  }

  ASSERT_TRUE(page.send(json{{"op", "pause"}, {"id", 4}}.dump()));
  EXPECT_TRUE(nextOfType(page, "reply")["ok"].get<bool>());
  EXPECT_TRUE(node_->worldState().paused);
  const std::uint64_t steps = node_->worldState().steps;
  ASSERT_TRUE(page.send(json{{"op", "step"}, {"id", 5}, {"steps", 25}}.dump()));
  EXPECT_TRUE(nextOfType(page, "reply")["ok"].get<bool>());
  EXPECT_EQ(node_->worldState().steps, steps + 25);

  // A bad request is answered, and the view runs on.
  ASSERT_TRUE(page.send("not json"));
  EXPECT_FALSE(nextOfType(page, "reply")["ok"].get<bool>());
  ASSERT_TRUE(page.send(json{{"op", "step"}, {"id", 6}, {"steps", -3}}.dump()));
  reply = nextOfType(page, "reply");
  EXPECT_FALSE(reply["ok"].get<bool>());
  EXPECT_EQ(reply["id"], 6);
}

TEST_F(ViewServerTest, TwentyPagesAndPagesDroppedMidTransferLeaveTheNodeRunning) {
  startNode(seedLaunch("mock"));
  startView(false);
  std::vector<std::unique_ptr<WsTestClient>> pages;
  for (int i = 0; i < 20; ++i) {
    pages.push_back(std::make_unique<WsTestClient>());
    ASSERT_TRUE(pages.back()->connect(url_)) << i << ": " << pages.back()->why();
  }
  ASSERT_TRUE(servoloop::testing::waitUntil([&] { return view_->pages() == 20; }, std::chrono::seconds(10)));
  for (auto& page : pages) ASSERT_TRUE(nextOfType(*page, "frame").is_object());
  // Ten pages go away without a word, some before reading what was sent.
  for (int i = 0; i < 10; ++i) pages[i]->abort();
  ASSERT_TRUE(servoloop::testing::waitUntil([&] { return view_->pages() == 10; }, std::chrono::seconds(20)));
  // The others still get frames of a world that runs on.
  const double t0 = node_->simTime();
  for (int i = 10; i < 20; ++i) {
    json frame;
    ASSERT_TRUE(servoloop::testing::waitUntil(
        [&] {
          frame = nextOfType(*pages[i], "frame", std::chrono::seconds(2));
          return frame.is_object() && frame["t"].get<double>() > t0;
        },
        std::chrono::seconds(20)))
        << i;
  }
  EXPECT_GT(node_->simTime(), t0);
  EXPECT_EQ(node_->findRobot(kRobot)->safety().state(), controller_manager::SafetyState::running);
}

TEST_F(ViewServerTest, AMeshIsServedAndAMissingOneIsAWarning) {
  TempDir dir("servoloop-view-mesh");
  const fs::path package = dir.path() / "mesh_bot";
  fs::create_directories(package / "meshes");
  servoloop::testing::writeFile(package / "package.xml", "<package><name>mesh_bot</name></package>");
  // A 0.1 m tetrahedron, ASCII STL.
  const std::string stl =
      "solid t\nfacet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0.1 0 0\nvertex 0 0.1 0\nendloop\nendfacet\n"
      "facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 0 0 0.1\nvertex 0.1 0 0\nendloop\nendfacet\nendsolid t\n";
  servoloop::testing::writeFile(package / "meshes" / "part.stl", stl);
  servoloop::testing::writeFile(package / "mesh_bot.urdf", R"(<robot name="mesh_bot">
  <link name="world"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="base">
    <visual><geometry><mesh filename="package://mesh_bot/meshes/part.stl" scale="2 2 2"/></geometry>
      <material name="red"><color rgba="1 0 0 1"/></material></visual>
    <visual><geometry><mesh filename="package://mesh_bot/meshes/gone.dae"/></geometry></visual>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
</robot>)");
  node::LaunchFile launch;
  launch.world.backend = "mock";
  node::RobotSpec robot;
  robot.urdf = package / "mesh_bot.urdf";
  launch.robots.push_back(robot);
  startNode(launch);
  startView(false);
  WsTestClient page;
  ASSERT_TRUE(page.connect(url_)) << page.why();
  const json scene = nextOfType(page, "scene");
  ASSERT_TRUE(scene.is_object());
  const json& visuals = scene["models"][0]["links"];
  json base;
  for (const json& link : visuals) {
    if (link["name"] == "base") base = link;
  }
  ASSERT_EQ(base["visuals"].size(), 2u) << scene.dump();
  const json& mesh = base["visuals"][0];
  EXPECT_EQ(mesh["geometry"]["format"], "stl");
  EXPECT_EQ(mesh["geometry"]["scale"], json::array({2.0, 2.0, 2.0}));
  EXPECT_EQ(mesh["color"], json::array({1.0, 0.0, 0.0, 1.0}));
  const auto served = servoloop::testing::httpGet("127.0.0.1", view_->port(), mesh["geometry"]["url"].get<std::string>());
  EXPECT_EQ(served.status, 200);
  EXPECT_EQ(served.body, stl);
  // The missing mesh: a URL that fails (the page then draws the collision
  // box) and a warning naming it.
  EXPECT_EQ(servoloop::testing::httpGet("127.0.0.1", view_->port(), base["visuals"][1]["geometry"]["url"].get<std::string>()).status,
            404);
  const json warning = nextOfType(page, "warning");
  ASSERT_TRUE(warning.is_object());
  EXPECT_NE(warning["text"].get<std::string>().find("gone.dae"), std::string::npos) << warning.dump();
}

}  // namespace
