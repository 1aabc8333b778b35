// control.gains (docs/node_operations.md): the gains of a controller's PIDs,
// and a change of one while it runs — what ros_control serves as the PID's
// dynamic_reconfigure (<controller>/pid/set_parameters).
#include <string>
#include <vector>

#include "request_fields.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/ipc/ipc_protocol.hpp"
#include "servoloop/node/node.hpp"
#include "servoloop/node/node_operations.hpp"
#include "servoloop/params/parameter_store.hpp"

namespace servoloop::node {

using nlohmann::json;

namespace {
// The request fields that change a gain, as control_toolbox's dynamic_reconfigure names them.
constexpr const char* kGainFields[] = {"p", "i", "d", "i_clamp_min", "i_clamp_max", "antiwindup"};

json gainsToJson(const controller_manager::PidGains& pid) {
  const controllers::Pid::Gains& g = pid.gains;
  return {{"name", pid.pid},         {"p", g.p_gain},           {"i", g.i_gain},
          {"d", g.d_gain},           {"i_clamp_min", g.i_min}, {"i_clamp_max", g.i_max},
          {"antiwindup", g.antiwindup}};
}
}  // namespace

json NodeOperations::controlGains(RobotInstance& robot, const json& request) {
  const std::string controller = ipc::requireRequestString(request, "controller");
  controller_manager::ControllerManager& manager = robot.manager();
  std::vector<controller_manager::PidGains> pids;
  throwIfFailed(manager.controllerGains(controller, pids));

  bool change = false;
  for (const char* field : kGainFields) change = change || ipc::findRequestField(request, field) != nullptr;
  if (change) {
    std::string pid_name = ipc::requestString(request, "pid", "");
    if (pid_name.empty()) {
      if (pids.size() != 1) {
        std::string names;
        for (const auto& pid : pids) names += (names.empty() ? "'" : ", '") + pid.pid + "'";
        throw Error("control.gains: controller '" + controller + "' has " +
                    (pids.empty() ? std::string("no PID") : "the PIDs " + names) +
                    (pids.empty() ? "" : "; name one with 'pid'"));
      }
      pid_name = pids.front().pid;
    }
    controller_manager::PidGains changed{pid_name, {}};
    for (const auto& pid : pids) {
      if (pid.pid == pid_name) changed.gains = pid.gains;
    }
    controllers::Pid::Gains& g = changed.gains;
    g.p_gain = ipc::requestNumber(request, "p", g.p_gain);
    g.i_gain = ipc::requestNumber(request, "i", g.i_gain);
    g.d_gain = ipc::requestNumber(request, "d", g.d_gain);
    g.i_min = ipc::requestNumber(request, "i_clamp_min", g.i_min);
    g.i_max = ipc::requestNumber(request, "i_clamp_max", g.i_max);
    g.antiwindup = ipc::requestBool(request, "antiwindup", g.antiwindup);
    throwIfFailed(manager.setControllerGains(controller, changed));

    // The parameters follow, as dynamic_reconfigure writes them to the
    // parameter server: a reload of the controller keeps the new gains.
    params::ParameterStore& store = node_.parameters();
    std::string prefix = robot.robotNamespace();
    if (prefix.empty() || prefix.back() != '/') prefix += '/';
    prefix += controller + "/" + pid_name + "/";
    store.set(prefix + "p", g.p_gain);
    store.set(prefix + "i", g.i_gain);
    store.set(prefix + "d", g.d_gain);
    store.set(prefix + "i_clamp_min", g.i_min);
    store.set(prefix + "i_clamp_max", g.i_max);
    store.set(prefix + "antiwindup", g.antiwindup);
    for (auto& pid : pids) {
      if (pid.pid == pid_name) pid.gains = g;
    }
  }
  json reply = json::array();
  for (const auto& pid : pids) reply.push_back(gainsToJson(pid));
  return {{"controller", controller}, {"pids", std::move(reply)}};
}

}  // namespace servoloop::node
