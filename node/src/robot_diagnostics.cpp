// robotDiagnostics: a robot's loop, safety and controllers as DiagnosticStatus entries.
#include "servoloop/node/robot_diagnostics.hpp"

#include <fmt/format.h>

#include "servoloop/node/robot_instance.hpp"

namespace servoloop::node {
namespace {

using diagnostic_msgs::DiagnosticStatus;

void addDuration(DiagnosticStatus& status, const std::string& what, const controller_manager::DurationSnapshot& d) {
  if (d.count == 0) return;
  status.values.push_back({what + " p50 (us)", fmt::format("{:.1f}", d.p50_s * 1e6)});
  status.values.push_back({what + " p99 (us)", fmt::format("{:.1f}", d.p99_s * 1e6)});
  status.values.push_back({what + " max (us)", fmt::format("{:.1f}", d.max_s * 1e6)});
}

}  // namespace

diagnostic_msgs::DiagnosticArray robotDiagnostics(RobotInstance& robot, std::uint64_t* previous_overruns) {
  diagnostic_msgs::DiagnosticArray array;
  array.stamp = robot.simTime();
  const std::string& ns = robot.robotNamespace();
  const controller_manager::LoopStatisticsSnapshot loop = robot.loop().statistics().snapshot();
  const controller_manager::SafetyState safety = robot.safety().state();

  DiagnosticStatus status;
  status.name = ns + ": control loop";
  status.hardware_id = robot.backendName();
  const bool overran = loop.overruns > *previous_overruns;
  *previous_overruns = loop.overruns;
  if (safety != controller_manager::SafetyState::running) {
    status.level = DiagnosticStatus::kError;
    status.message = robot.safety().reason();
  } else if (overran) {
    status.level = DiagnosticStatus::kWarn;
    status.message = "cycles overran their deadline since the last report";
  } else {
    status.message = "running";
  }
  status.values.push_back({"safety state", controller_manager::toString(safety)});
  status.values.push_back({"cycles", std::to_string(loop.cycles)});
  status.values.push_back({"overruns", std::to_string(loop.overruns)});
  status.values.push_back({"hardware errors", std::to_string(loop.hardware_errors)});
  status.values.push_back({"real-time factor", fmt::format("{:.3f}", loop.real_time_factor)});
  controller_manager::DurationSnapshot cycle;
  cycle.count = loop.timed_cycles;
  cycle.p50_s = loop.compute_p50_s;
  cycle.p99_s = loop.compute_p99_s;
  cycle.max_s = loop.compute_max_s;
  addDuration(status, "cycle", cycle);
  addDuration(status, "read", loop.read);
  addDuration(status, "write", loop.write);
  addDuration(status, "wake-up latency", loop.wakeup_latency);
  addDuration(status, "period jitter", loop.period_jitter);
  array.status.push_back(std::move(status));

  const auto times = robot.manager().updateTimes();
  for (const controller_manager::ControllerSpec& controller : robot.manager().listControllers()) {
    DiagnosticStatus entry;
    entry.name = ns + ": " + controller.name;
    entry.hardware_id = controller.type;
    entry.message = toString(controller.state);
    if (controller.state == controller_manager::ControllerState::failed) {
      entry.level = DiagnosticStatus::kError;
      entry.message = controller.last_fault;
    } else if (controller.state != controller_manager::ControllerState::running) {
      entry.level = DiagnosticStatus::kWarn;
    }
    for (const auto& [name, time] : times) {
      if (name == controller.name) addDuration(entry, "update", time);
    }
    array.status.push_back(std::move(entry));
  }
  return array;
}

void RobotInstance::publishDiagnosticsIfDue() {
  constexpr std::chrono::seconds kInterval{1};
  const auto now = std::chrono::steady_clock::now();
  if (now < next_diagnostics_) return;
  next_diagnostics_ = now + kInterval;
  bus_->publish(params::resolveName(namespace_, "diagnostics"), robotDiagnostics(*this, &diagnostics_overruns_));
}

}  // namespace servoloop::node
