#include "view_connection.hpp"

namespace servoloop::cli {

view::NodeRequest nodeRequestOver(servoloop::ipc::IpcClient client) {
  auto shared = std::make_shared<servoloop::ipc::IpcClient>(std::move(client));
  // A world step or reset waits for the world's loop.
  return [shared](const nlohmann::json& request) { return shared->request(request, 600.0); };
}

CLI::Option* addViewControlFlag(CLI::App& command, bool& control) {
  return command.add_flag("--view-control", control,
                          "The page may start and stop controllers, engage and release the emergency stop, and "
                          "pause, step and reset the world (read-only without it)");
}

}  // namespace servoloop::cli
