// The view's page in a real browser: Debian's headless Chromium, driven over
// the DevTools protocol, against a running node (the seed robot on the mock
// backend, paused so that nothing moves unless the test moves it). The
// robot's pixels move when its joint moves (screenshots compared), the
// controller list on the page is the node's, and the page's emergency-stop
// button engages the node's emergency stop.
#include <stdlib.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "chromium_page.hpp"
#include "node_test_support.hpp"
#include "servoloop/ipc/ipc_client.hpp"
#include "servoloop/node/node.hpp"
#include "servoloop/view/view_server.hpp"
#include "temp_dir.hpp"
#include "wait_until.hpp"

namespace {

using namespace servoloop;
using namespace servoloop::node_test;
using nlohmann::json;
using servoloop::testing::ChromiumPage;

constexpr const char* kRobot = "/one_DOF_robot";

class ViewInBrowser : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(ChromiumPage::available()) << "the browser tests need Debian's Chromium: apt install chromium";
    ASSERT_TRUE(backendAvailable("mock"));
    ::setenv("SERVOLOOP_RUN_DIR", run_dir_.path().c_str(), 1);
    if (!std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()).starts_with("Meshes")) {
      open(seedLaunch("mock"));
    }
  }
  // The world of `launch`, paused, its view with control, and the page, ready.
  void open(const node::LaunchFile& launch) {
    node::NodeOptions options;
    options.real_time_factor = 1.0;
    options.start_paused = true;
    node_ = std::make_unique<node::Node>(launch, options);
    node_->start();
    ASSERT_TRUE(ipc::waitForNode("/", 5.0));
    view::ViewOptions view_options;
    view_options.port = 0;
    view_options.control = true;
    view_ = std::make_unique<view::ViewServer>(view_options, [] {
      auto client = std::make_shared<ipc::IpcClient>(ipc::IpcClient::connectToNode("/"));
      return view::NodeRequest([client](const json& request) { return client->request(request, 30.0); });
    });
    view_->start();
    page_ = std::make_unique<ChromiumPage>(browser_dir_.path(), view_->url(), 800, 600);
    ASSERT_TRUE(servoloop::testing::waitUntil(
        [&] { return page_->evaluate("!!(window.servoloopView && window.servoloopView.ready)") == true; },
        std::chrono::seconds(60)))
        << "the page never became ready: " << page_->exceptionText() << "\n" << page_->log();
  }
  void TearDown() override {
    page_.reset();
    view_.reset();
    node_.reset();
    ::unsetenv("SERVOLOOP_RUN_DIR");
  }

  // Two animation frames: what the page has is on the canvas.
  void settle() { page_->evaluate("new Promise(r => requestAnimationFrame(() => requestAnimationFrame(() => r(true))))"); }

  TempDir run_dir_{"servoloop-view-browser-run"};
  TempDir browser_dir_{"servoloop-view-browser"};
  std::unique_ptr<node::Node> node_;
  std::unique_ptr<view::ViewServer> view_;
  std::unique_ptr<ChromiumPage> page_;
};

TEST_F(ViewInBrowser, TheRobotsPixelsMoveWhenItsJointMoves) {
  // The pictures are of the world: the time and real-time factor overlaid
  // on it (which change on their own) and the side panel are hidden.
  ASSERT_EQ(page_->evaluate("['hud', 'panel'].forEach(id => document.getElementById(id).style.visibility = 'hidden'), true"),
            true)
      << page_->exceptionText();
  settle();
  const servoloop::testing::RgbaImage before = page_->screenshot();
  ASSERT_GT(before.width, 0u);
  settle();
  const servoloop::testing::RgbaImage still = page_->screenshot();
  // Nothing moved: the same picture (so what differs below is the joint).
  EXPECT_LT(servoloop::testing::differingPixels(before, still), 50u) << servoloop::testing::differingBox(before, still);

  node_->setModelConfiguration(kRobot, {"joint1"}, {1.2});
  ASSERT_TRUE(servoloop::testing::waitUntil(
      [&] {
        const json q = page_->evaluate("window.servoloopView.lastFrame.models[0].q[0]");
        return q.is_number() && std::abs(q.get<double>() - 1.2) < 1e-9;
      },
      std::chrono::seconds(20)));
  settle();
  const servoloop::testing::RgbaImage after = page_->screenshot();
  // The 1 m arm swung 1.2 rad: thousands of pixels change at 800 x 600.
  EXPECT_GT(servoloop::testing::differingPixels(before, after), 2000u);

  // And back: the picture of the start again.
  node_->setModelConfiguration(kRobot, {"joint1"}, {0.0});
  ASSERT_TRUE(servoloop::testing::waitUntil(
      [&] {
        const json q = page_->evaluate("window.servoloopView.lastFrame.models[0].q[0]");
        return q.is_number() && std::abs(q.get<double>()) < 1e-9;
      },
      std::chrono::seconds(20)));
  settle();
  EXPECT_LT(servoloop::testing::differingPixels(before, page_->screenshot()), 50u);
}

TEST_F(ViewInBrowser, TheControllerListIsTheNodesAndFollowsIt) {
  ipc::IpcClient client = ipc::IpcClient::connectToNode(kRobot);
  auto node_list = [&] {
    json list = json::array();
    const json reply = client.call("control.list");
    for (const json& controller : reply["controllers"]) {
      list.push_back({controller["name"], controller["state"]});
    }
    return list;
  };
  const std::string page_list =
      "[...document.querySelectorAll('#controllers div.robot[data-ns=\"/one_DOF_robot\"] div.controller')]"
      ".map(e => [e.dataset.name, e.dataset.state])";
  json shown;
  // Until the page shows what the node lists.
  const auto pageShowsTheNodesList = [&] {
    return servoloop::testing::waitUntil(
        [&] {
          shown = page_->evaluate(page_list);
          return shown == node_list();
        },
        std::chrono::seconds(20));
  };
  ASSERT_TRUE(pageShowsTheNodesList()) << "page: " << shown.dump() << " node: " << node_list().dump();
  EXPECT_EQ(shown.size(), 2u);

  // Stopped through the command line's socket (a switch is carried out by a
  // cycle: the world runs): the page follows.
  node_->unpauseWorld();
  client.call("control.switch", {{"stop", {"joint1_position_controller"}}});
  ASSERT_TRUE(pageShowsTheNodesList()) << "page: " << shown.dump() << " node: " << node_list().dump();
  EXPECT_EQ(shown[1][1], "stopped");
}

TEST_F(ViewInBrowser, TheEmergencyStopButtonEngagesTheEmergencyStop) {
  auto* robot = node_->findRobot(kRobot);
  ASSERT_FALSE(robot->safety().emergencyStopLatched());
  const json clicked = page_->evaluate(
      "(() => { const b = document.querySelector('#controllers div.robot[data-ns=\"/one_DOF_robot\"] button.estop');"
      " if (!b) return false; b.click(); return true; })()");
  ASSERT_EQ(clicked, true) << "no emergency-stop button on the page: " << page_->exceptionText();
  ASSERT_TRUE(servoloop::testing::waitUntil([&] { return robot->safety().emergencyStopLatched(); }, std::chrono::seconds(20)));
  EXPECT_EQ(robot->safety().state(), controller_manager::SafetyState::emergency_stop);
}

// A fixed base with four links side by side, one visual mesh each: an
// ASCII STL (in the URDF's red), an OBJ with its material library (green),
// a COLLADA file with its own material (blue; Z up) and a mesh that is not
// there, whose link the page draws from its collision box.
TEST_F(ViewInBrowser, MeshesOfEveryFormatAndAMissingOne) {
  const std::filesystem::path package = browser_dir_.path() / "mesh_bot";
  std::filesystem::create_directories(package / "meshes");
  servoloop::testing::writeFile(package / "package.xml", "<package><name>mesh_bot</name></package>");
  servoloop::testing::writeFile(package / "meshes" / "part.stl",
                                "solid p\nfacet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0.1 0 0\nvertex 0 0.1 0\n"
                                "endloop\nendfacet\nfacet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 0 0 0.1\n"
                                "vertex 0.1 0 0\nendloop\nendfacet\nendsolid p\n");
  servoloop::testing::writeFile(package / "meshes" / "part.obj",
                                "mtllib part.mtl\no part\nv 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nusemtl green\n"
                                "f 1 2 3\nf 1 2 4\n");
  servoloop::testing::writeFile(package / "meshes" / "part.mtl", "newmtl green\nKd 0 1 0\n");
  servoloop::testing::writeFile(package / "meshes" / "part.dae", R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Z_UP</up_axis></asset>
  <library_effects><effect id="blue-effect"><profile_COMMON><technique sid="common"><phong>
    <diffuse><color sid="diffuse">0 0 1 1</color></diffuse></phong></technique></profile_COMMON></effect></library_effects>
  <library_materials><material id="blue" name="blue"><instance_effect url="#blue-effect"/></material></library_materials>
  <library_geometries><geometry id="tri" name="tri"><mesh>
    <source id="tri-pos"><float_array id="tri-pos-array" count="12">0 0 0 0.1 0 0 0 0.1 0 0 0 0.1</float_array>
      <technique_common><accessor source="#tri-pos-array" count="4" stride="3"><param name="X" type="float"/>
        <param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
    <vertices id="tri-vtx"><input semantic="POSITION" source="#tri-pos"/></vertices>
    <triangles material="mat" count="2"><input semantic="VERTEX" source="#tri-vtx" offset="0"/><p>0 1 2 0 1 3</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="Scene" name="Scene"><node id="part" name="part">
    <instance_geometry url="#tri"><bind_material><technique_common><instance_material symbol="mat" target="#blue"/>
    </technique_common></bind_material></instance_geometry></node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#Scene"/></scene>
</COLLADA>
)");
  std::string links, joints;
  const char* names[] = {"stl_link", "obj_link", "dae_link", "gone_link"};
  const char* files[] = {"part.stl", "part.obj", "part.dae", "gone.dae"};
  for (int i = 0; i < 4; ++i) {
    links += std::string("<link name=\"") + names[i] + "\"><visual><geometry><mesh filename=\"package://mesh_bot/meshes/" +
             files[i] + "\"/></geometry><material name=\"red\"><color rgba=\"1 0 0 1\"/></material></visual>"
             "<collision><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision></link>\n";
    joints += std::string("<joint name=\"j") + std::to_string(i) + "\" type=\"fixed\"><parent link=\"base\"/><child link=\"" +
              names[i] + "\"/><origin xyz=\"" + std::to_string(0.3 * i) + " 0 0.5\"/></joint>\n";
  }
  servoloop::testing::writeFile(package / "mesh_bot.urdf", "<robot name=\"mesh_bot\"><link name=\"world\"/>"
                                "<joint name=\"fix\" type=\"fixed\"><parent link=\"world\"/><child link=\"base\"/></joint>"
                                "<link name=\"base\"/>\n" + links + joints + "</robot>");
  node::LaunchFile launch;
  launch.world.backend = "mock";
  node::RobotSpec robot;
  robot.urdf = package / "mesh_bot.urdf";
  launch.robots.push_back(robot);
  open(launch);
  ASSERT_FALSE(HasFatalFailure());

  // Each link's meshes: material colour, opacity, and world bounding box.
  const json links_drawn = page_->evaluate(R"((() => {
    const out = {};
    window.servoloopView.scene3.updateMatrixWorld(true);
    window.servoloopView.scene3.traverse(o => {
      if (!o.isMesh || !o.visible) return;
      let link = o.parent;
      while (link && !/_link$/.test(link.name)) link = link.parent;
      if (!link) return;
      const box = new THREE.Box3().setFromObject(o);
      (out[link.name] = out[link.name] || []).push({
        color: o.material.color.toArray(), opacity: o.material.opacity,
        min: box.min.toArray(), max: box.max.toArray()});
    });
    return out;
  })())");
  ASSERT_TRUE(links_drawn.is_object()) << page_->exceptionText();
  auto expectColor = [&](const char* link, std::vector<double> rgb) {
    ASSERT_TRUE(links_drawn.contains(link)) << link << ": " << links_drawn.dump();
    const json& mesh = links_drawn[link][0];
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(mesh["color"][c].get<double>(), rgb[c], 1e-6) << link << " " << mesh.dump();
    EXPECT_DOUBLE_EQ(mesh["opacity"].get<double>(), 1.0) << link;
  };
  expectColor("stl_link", {1, 0, 0});  // the URDF's colour: an STL has none
  expectColor("obj_link", {0, 1, 0});  // its .mtl's Kd
  expectColor("dae_link", {0, 0, 1});  // its own material
  // Z up as the file says: the tetrahedron from the link's origin (x = 0.6, z = 0.5) up 0.1 m.
  const json& dae = links_drawn["dae_link"][0];
  EXPECT_NEAR(dae["min"][0].get<double>(), 0.6, 1e-6);
  EXPECT_NEAR(dae["min"][2].get<double>(), 0.5, 1e-6);
  EXPECT_NEAR(dae["max"][2].get<double>(), 0.6, 1e-6);
  EXPECT_NEAR(dae["max"][1].get<double>(), 0.1, 1e-6);
  // The missing mesh: its link's collision box, translucent, 0.1 m around the link's origin.
  ASSERT_TRUE(links_drawn.contains("gone_link")) << links_drawn.dump();
  const json& fallback = links_drawn["gone_link"][0];
  EXPECT_LT(fallback["opacity"].get<double>(), 1.0);
  EXPECT_NEAR(fallback["min"][0].get<double>(), 0.9 - 0.05, 1e-6);
  EXPECT_NEAR(fallback["max"][2].get<double>(), 0.5 + 0.05, 1e-6);
  EXPECT_EQ(page_->evaluate("window.servoloopView.meshFailures"), 1);
  const json warnings = page_->evaluate("[...document.querySelectorAll('#warnings li')].map(e => e.textContent)");
  ASSERT_TRUE(warnings.is_array());
  bool named = false;
  for (const json& warning : warnings) named |= warning.get<std::string>().find("gone.dae") != std::string::npos;
  EXPECT_TRUE(named) << warnings.dump();
}

}  // namespace
