#include "controller_manager_services.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <controller_manager_msgs/ListControllerTypes.h>
#include <controller_manager_msgs/ListControllers.h>
#include <controller_manager_msgs/LoadController.h>
#include <controller_manager_msgs/ReloadControllerLibraries.h>
#include <controller_manager_msgs/SwitchController.h>
#include <controller_manager_msgs/UnloadController.h>
#include <ros/ros.h>

#include "parameter_bridge.hpp"

namespace servoloop::ros1 {

using nlohmann::json;
namespace cmm = controller_manager_msgs;

const char* rosControlState(const std::string& servoloop_state) {
  if (servoloop_state == "running") return "running";
  if (servoloop_state == "stopped") return "stopped";
  if (servoloop_state == "failed") return "aborted";
  return "initialized";  // constructed, initialized: loaded, never started
}

std::string rosControlInterfaceName(const std::string& servoloop_interface) {
  if (servoloop_interface.empty() || servoloop_interface.find("::") != std::string::npos) return servoloop_interface;
  return "hardware_interface::" + servoloop_interface;
}

namespace {

// Runs a node operation for a service whose response is `ok`; a refusal is
// ok=false with the node's reason in the log, as ros_control logs its errors.
bool callForOk(NodeLink& link, const char* service, std::string_view op, const json& args, double timeout_s = 10.0) {
  try {
    link.call(op, args, timeout_s);
    return true;
  } catch (const std::exception& e) {
    ROS_ERROR("%s: %s", service, e.what());
    return false;
  }
}

}  // namespace

ControllerManagerServices::ControllerManagerServices(ros::NodeHandle& nh, NodeLink& link, YAML::Node copied_parameters)
    : copied_parameters_(std::move(copied_parameters)) {
  const std::string base = link.resolve("controller_manager") + "/";

  servers_.push_back(nh.advertiseService<cmm::ListControllers::Request, cmm::ListControllers::Response>(
      base + "list_controllers", [&link](cmm::ListControllers::Request&, cmm::ListControllers::Response& response) {
        const json reply = link.call("control.list");
        for (const json& controller : reply.at("controllers")) {
          cmm::ControllerState& state = response.controller.emplace_back();
          state.name = controller.value("name", "");
          state.type = controller.value("type", "");
          state.state = rosControlState(controller.value("state", ""));
          for (const json& claim : controller.value("claimed_resources", json::array())) {
            cmm::HardwareInterfaceResources& resources = state.claimed_resources.emplace_back();
            resources.hardware_interface = rosControlInterfaceName(claim.value("hardware_interface", ""));
            resources.resources = claim.value("resources", std::vector<std::string>{});
          }
        }
        return true;
      }));

  servers_.push_back(nh.advertiseService<cmm::ListControllerTypes::Request, cmm::ListControllerTypes::Response>(
      base + "list_controller_types",
      [&link](cmm::ListControllerTypes::Request&, cmm::ListControllerTypes::Response& response) {
        const json reply = link.call("control.list_types");
        for (const json& type : reply.at("types")) {
          if (type.value("kind", "") != "controller") continue;
          response.types.push_back(type.value("type", ""));
          response.base_classes.emplace_back("controller_interface::ControllerBase");
        }
        return true;
      }));

  servers_.push_back(nh.advertiseService<cmm::LoadController::Request, cmm::LoadController::Response>(
      base + "load_controller",
      [this, &link](cmm::LoadController::Request& request, cmm::LoadController::Response& response) {
        std::lock_guard lock(load_mutex_);
        // As ros_control does, the configuration is what the ROS parameter
        // server holds when the controller is loaded.
        try {
          passControllerParametersOn(link, request.name, copied_parameters_, synced_parameters_);
        } catch (const std::exception& e) {
          ROS_ERROR("load_controller: the parameters of %s on the ROS parameter server could not be passed to "
                    "servoloop: %s",
                    request.name.c_str(), e.what());
          response.ok = false;
          return true;
        }
        response.ok = callForOk(link, "load_controller", "control.load", {{"name", request.name}});
        return true;
      }));

  servers_.push_back(nh.advertiseService<cmm::UnloadController::Request, cmm::UnloadController::Response>(
      base + "unload_controller",
      [&link](cmm::UnloadController::Request& request, cmm::UnloadController::Response& response) {
        response.ok = callForOk(link, "unload_controller", "control.unload", {{"name", request.name}});
        return true;
      }));

  servers_.push_back(nh.advertiseService<cmm::SwitchController::Request, cmm::SwitchController::Response>(
      base + "switch_controller",
      [&link](cmm::SwitchController::Request& request, cmm::SwitchController::Response& response) {
        std::string strictness;
        if (request.strictness == cmm::SwitchController::Request::STRICT) {
          strictness = "strict";
        } else if (request.strictness == cmm::SwitchController::Request::BEST_EFFORT || request.strictness == 0) {
          // ros_control takes an unset strictness (0) as BEST_EFFORT.
          strictness = "best_effort";
        } else {
          ROS_ERROR("switch_controller: strictness %d is neither BEST_EFFORT (1) nor STRICT (2)", request.strictness);
          response.ok = false;
          return true;
        }
        // At most an hour: the bridge waits for the node's answer that long.
        const double timeout =
            std::isfinite(request.timeout) && request.timeout > 0.0 ? std::min(request.timeout, 3600.0) : 0.0;
        json args = {{"start", request.start_controllers}, {"stop", request.stop_controllers},
                     {"strictness", strictness}, {"start_asap", static_cast<bool>(request.start_asap)}};
        if (timeout > 0.0) args["timeout"] = timeout;
        // The node answers once the switch happened (or failed); a switch with
        // no timeout is given 30 s (the node answers within cycles unless its loop waits).
        response.ok = callForOk(link, "switch_controller", "control.switch", args, timeout > 0.0 ? timeout + 5.0 : 30.0);
        return true;
      }));

  servers_.push_back(
      nh.advertiseService<cmm::ReloadControllerLibraries::Request, cmm::ReloadControllerLibraries::Response>(
          base + "reload_controller_libraries",
          [&link](cmm::ReloadControllerLibraries::Request& request, cmm::ReloadControllerLibraries::Response& response) {
            response.ok = callForOk(link, "reload_controller_libraries", "control.reload_libraries",
                                    {{"force_kill", static_cast<bool>(request.force_kill)}});
            return true;
          }));
}

}  // namespace servoloop::ros1
