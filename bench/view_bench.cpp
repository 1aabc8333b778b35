// What the browser view costs the world's loop, as users run it: a node
// (node::Node, as `servoloop launch` builds and runs it, free-running) of
// the shared world of 4 seed arms and 16 boxes on bullet (world_fixture.hpp),
// 5 s of 1 ms steps:
//
//   raw          the same world stepped by hand on raw Bullet
//   node         the node alone (no sockets, no view)
//   view, N pages  the node with its sockets, `--view` serving, and N pages
//                open (WebSocket clients taking every message, as a browser
//                does): the view reads a frame over the node's socket at up
//                to 60 per second of wall time, the world takes its snapshots
//                between segments at 60 Hz of world time
//
// Wall time of the run, alternating, median of 5; every ratio is of medians
// of this one run. Then, with the world at real time (real-time factor 1)
// for 3 s, the frames each page received per second, with 1 and 10 pages.
#include <stdlib.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_support.hpp"
#include "loop_fixtures.hpp"
#include "servoloop/ipc/ipc_client.hpp"
#include "servoloop/node/launch_file.hpp"
#include "servoloop/node/node.hpp"
#include "servoloop/view/view_server.hpp"
#include "world_fixture.hpp"
#include "ws_test_client.hpp"

namespace servoloop::bench {
namespace {

namespace fs = std::filesystem;
constexpr std::uint64_t kSteps = 5000;
constexpr int kArms = 4;
constexpr int kRepetitions = 5;

struct PageRun {
  double wall_s = 0.0;
  double frames_per_page_per_s = 0.0;
};

// One run of the node for `duration_s` of world time with `pages` pages open
// (pages < 0: no sockets and no view at all).
PageRun runNode(const WorldFiles& files, int pages, double duration_s, double real_time_factor) {
  node::NodeOptions options;
  options.serve_ipc = pages >= 0;
  options.real_time_factor = real_time_factor;
  options.duration_s = duration_s;
  node::Node node(node::parseLaunchFile(worldLaunchText("bullet", kArms, true), "bench", files.dir), options);
  std::unique_ptr<view::ViewServer> server;
  std::vector<std::unique_ptr<testing::WsTestClient>> clients;
  if (pages >= 0) {
    view::ViewOptions view_options;
    view_options.port = 0;
    server = std::make_unique<view::ViewServer>(view_options, [] {
      auto client = std::make_shared<ipc::IpcClient>(ipc::IpcClient::connectToNode("/"));
      return view::NodeRequest([client](const nlohmann::json& request) { return client->request(request, 30.0); });
    });
    server->start();
    for (int p = 0; p < pages; ++p) {
      clients.push_back(std::make_unique<testing::WsTestClient>());
      if (!clients.back()->connect("ws://127.0.0.1:" + std::to_string(server->port()) + "/ws")) {
        std::fprintf(stderr, "view bench: page %d did not connect: %s\n", p, clients.back()->why().c_str());
      }
    }
  }
  // Every page takes what it is sent, as a browser does.
  std::atomic<bool> reading{true};
  std::atomic<std::uint64_t> frames{0};
  std::vector<std::thread> readers;
  for (auto& client : clients) {
    readers.emplace_back([&, page = client.get()] {
      while (reading) {
        const auto text = page->receive(std::chrono::milliseconds(50));
        if (text && text->find("\"type\":\"frame\"") != std::string::npos) ++frames;
      }
    });
  }
  const std::uint64_t frames_before = frames.load();
  const auto start = std::chrono::steady_clock::now();
  node.start();
  node.waitUntilDone({}, std::chrono::milliseconds(5));
  const auto end = std::chrono::steady_clock::now();
  PageRun run;
  run.wall_s = std::chrono::duration<double>(end - start).count();
  if (pages > 0) run.frames_per_page_per_s = double(frames.load() - frames_before) / pages / run.wall_s;
  reading = false;
  for (auto& reader : readers) reader.join();
  clients.clear();
  if (server) server->stop();
  node.shutdown();
  return run;
}

}  // namespace
}  // namespace servoloop::bench

int main() {
  using namespace servoloop::bench;
  // The node's sockets in a folder of this run's own.
  const fs::path run_dir = fs::temp_directory_path() / ("servoloop-view-bench-" + std::to_string(::getpid()));
  fs::create_directories(run_dir);
  fs::permissions(run_dir, fs::perms::owner_all, fs::perm_options::replace);
  ::setenv("SERVOLOOP_RUN_DIR", run_dir.c_str(), 1);
  const WorldFiles files(kArms);
  const double duration_s = static_cast<double>(kSteps) * kTimeStepS;

  std::vector<double> raw, alone, view0, view1, view10;
  for (int r = 0; r < kRepetitions; ++r) {
    raw.push_back(runRawBulletWorld(files, kArms, kSteps).wall_s);
    alone.push_back(runNode(files, -1, duration_s, 0.0).wall_s);
    view0.push_back(runNode(files, 0, duration_s, 0.0).wall_s);
    view1.push_back(runNode(files, 1, duration_s, 0.0).wall_s);
    view10.push_back(runNode(files, 10, duration_s, 0.0).wall_s);
  }
  const double raw_s = median(raw), alone_s = median(alone);
  std::printf("=== The view's cost: %d seed arms and %d boxes on bullet, %llu steps of 1 ms, free-running; wall time, "
              "median of %d ===\n",
              kArms, kWorldBoxes, static_cast<unsigned long long>(kSteps), kRepetitions);
  std::printf("%-22s %12s %14s %14s\n", "run", "wall (ms)", "÷ raw bullet", "÷ node alone");
  std::printf("%-22s %12.1f %14.3f %14s\n", "raw bullet", raw_s * 1e3, 1.0, "-");
  std::printf("%-22s %12.1f %14.3f %14.3f\n", "node alone", alone_s * 1e3, alone_s / raw_s, 1.0);
  const std::pair<const char*, const std::vector<double>*> rows[] = {
      {"view, 0 pages", &view0}, {"view, 1 page", &view1}, {"view, 10 pages", &view10}};
  for (const auto& [name, values] : rows) {
    const double s = median(*values);
    std::printf("%-22s %12.1f %14.3f %14.3f\n", name, s * 1e3, s / raw_s, s / alone_s);
  }

  std::printf("=== Frames each page received per second, the world at real time (3 s) ===\n");
  for (const int pages : {1, 10}) {
    const PageRun run = runNode(files, pages, 3.0, 1.0);
    std::printf("%2d page(s): %.1f frames per second each\n", pages, run.frames_per_page_per_s);
  }
  std::error_code ec;
  fs::remove_all(run_dir, ec);
  return 0;
}
