// The view operations of a node's IPC sockets (docs/node_operations.md),
// what a browser view (servoloop's view/ module) reads of the world:
// view.scene, every simulated model with its URDF, and view.frame, every
// model's base pose and joint positions from the world's latest snapshot.
#include <filesystem>
#include <string>

#include "servoloop/node/node.hpp"
#include "servoloop/node/node_operations.hpp"

namespace servoloop::node {

using nlohmann::json;

json NodeOperations::viewOp(const std::string& op) {
  if (op == "view.scene") {
    json models = json::array();
    for (RobotInstance* robot : node_.robots()) {
      std::error_code error;
      const std::filesystem::path path = std::filesystem::absolute(robot->urdfPath(), error);
      models.push_back({{"name", robot->robotName()},
                        {"ns", robot->robotNamespace()},
                        {"urdf", robot->robotDescription()},
                        {"path", (error ? robot->urdfPath() : path).string()},
                        {"simulated", !robot->wallClock()}});
    }
    return {{"models", std::move(models)}, {"ground_plane", node_.launchFile().world.ground_plane}};
  }
  if (op == "view.frame") {
    WorldSnapshot::Frame frame;
    // A world on the wall clock has no world loop and so no snapshots: its
    // frames hold no model (the view says why), only the time.
    if (!node_.worldFrame(frame)) frame.sim_time_s = node_.simTime();
    const WorldState state = node_.worldState();
    json models = json::array();
    for (const WorldSnapshot::ModelFrame& model : frame.models) {
      models.push_back({{"ns", model.ns},
                        {"pose", std::vector<double>(std::begin(model.pose), std::end(model.pose))},
                        {"joint_names", model.joint_names},
                        {"q", model.joint_positions}});
    }
    return {{"generation", frame.generation}, {"steps", frame.steps},       {"sim_time", frame.sim_time_s},
            {"paused", state.paused},         {"models", std::move(models)}};
  }
  throw Error("unknown op '" + op + "'; the view reads view.{scene,frame}");
}

}  // namespace servoloop::node
