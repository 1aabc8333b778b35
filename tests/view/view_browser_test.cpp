// The view's page in a real browser: Debian's headless Chromium, driven over
// the DevTools protocol, against a running node (the seed robot on the mock
// backend, paused so that nothing moves unless the test moves it). The
// robot's pixels move when its joint moves (screenshots compared), the
// controller list on the page is the node's, and the page's emergency-stop
// button engages the node's emergency stop.
#include <stdlib.h>

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "chromium_page.hpp"
#include "node_test_support.hpp"
#include "servoloop/ipc/ipc_client.hpp"
#include "servoloop/node/node.hpp"
#include "servoloop/view/view_server.hpp"
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
    node::NodeOptions options;
    options.real_time_factor = 1.0;
    options.start_paused = true;
    node_ = std::make_unique<node::Node>(seedLaunch("mock"), options);
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
  ASSERT_TRUE(servoloop::testing::waitUntil(
      [&] {
        shown = page_->evaluate(page_list);
        return shown == node_list();
      },
      std::chrono::seconds(20)))
      << "page: " << shown.dump() << " node: " << node_list().dump();
  EXPECT_EQ(shown.size(), 2u);

  // Stopped through the command line's socket (a switch is carried out by a
  // cycle: the world runs): the page follows.
  node_->unpauseWorld();
  client.call("control.switch", {{"stop", {"joint1_position_controller"}}});
  ASSERT_TRUE(servoloop::testing::waitUntil(
      [&] {
        shown = page_->evaluate(page_list);
        return shown == node_list();
      },
      std::chrono::seconds(20)))
      << "page: " << shown.dump() << " node: " << node_list().dump();
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

}  // namespace
