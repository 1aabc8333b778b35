#pragma once
// What `servoloop launch --view` and `servoloop view` share: the view's
// requests carried over a node connection, and the --view-control flag.
#include <memory>

#include <CLI/CLI.hpp>

#include "servoloop/ipc/ipc_client.hpp"
#include "servoloop/view/view_server.hpp"

namespace servoloop::cli {

// Requests over `client` (one thread at a time, as the view uses each).
view::NodeRequest nodeRequestOver(servoloop::ipc::IpcClient client);

// --view-control: the page may start and stop controllers, engage the
// emergency stop, and pause, step and reset the world.
CLI::Option* addViewControlFlag(CLI::App& command, bool& control);

}  // namespace servoloop::cli
