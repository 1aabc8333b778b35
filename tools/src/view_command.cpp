// `servoloop view [HOST:]PORT [--view-control]`: the browser view
// (docs/view.md) of the world running in another process, reached through
// its sockets as the other commands reach it; until Ctrl-C.
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "command_registry.hpp"
#include "node_connection.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/view/view_server.hpp"
#include "view_connection.hpp"

namespace servoloop::cli {
namespace {

struct ViewCommandOptions {
  std::string address = "8080";
  bool control = false;
};

void runView(const ViewCommandOptions& options) {
  view::ViewOptions view_options;
  view::parseViewAddress(options.address, view_options);
  view_options.control = options.control;
  connectToWorld();  // a clear error now when no world runs
  view::ViewServer server(view_options, [] { return nodeRequestOver(connectToWorld()); });
  server.start();
  installStopSignalHandlers();
  logger().info("view: open {} in a browser{}; stop it with Ctrl-C", server.url(),
                options.control ? " (it may control the robots and the world)" : "");
  while (sleepUnlessStopped(3600.0)) {
  }
  server.stop();
}

void addViewCommand(CLI::App& root) {
  auto options = std::make_shared<ViewCommandOptions>();
  CLI::App* view = root.add_subcommand(
      "view", "Show the running world in 3D in a browser (three.js), served on HOST:PORT (default 127.0.0.1:8080)");
  view->add_option("address", options->address, "Where to serve the page: PORT, :PORT or HOST:PORT (default 8080)")
      ->type_name("[HOST:]PORT");
  addViewControlFlag(*view, options->control);
  view->callback([options] { runView(*options); });
}

}  // namespace
}  // namespace servoloop::cli

SERVOLOOP_CLI_COMMANDS(17, servoloop::cli::addViewCommand)
