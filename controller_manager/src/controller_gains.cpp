// ControllerManager's gain services: the gains of a loaded controller's
// tunable PIDs, and a change of one while the controller runs.
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "controller_entry.hpp"
#include "servoloop/controller_manager/controller_manager.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::controller_manager {

namespace {
// The first gain of a set that is not finite, or nullptr.
const char* firstNonFiniteGain(const controllers::Pid::Gains& gains) {
  if (!std::isfinite(gains.p_gain)) return "p";
  if (!std::isfinite(gains.i_gain)) return "i";
  if (!std::isfinite(gains.d_gain)) return "d";
  if (!std::isfinite(gains.i_min)) return "i_clamp_min";
  if (!std::isfinite(gains.i_max)) return "i_clamp_max";
  return nullptr;
}
}  // namespace

ServiceResult ControllerManager::controllerGains(const std::string& name, std::vector<PidGains>& gains) {
  gains.clear();
  std::lock_guard<std::mutex> lock(services_mutex_);
  const detail::ControllerEntry* entry = findEntry(name);
  if (entry == nullptr) return fail("gains of controller '" + name + "': no controller of that name is loaded");
  for (const TunablePid& tunable : entry->controller->tunablePids()) {
    gains.push_back(PidGains{tunable.name, tunable.pid->getGains()});
  }
  return ServiceResult::success();
}

ServiceResult ControllerManager::setControllerGains(const std::string& name, const PidGains& gains) {
  std::lock_guard<std::mutex> lock(services_mutex_);
  const std::string what = "set gains of controller '" + name + "'";
  const detail::ControllerEntry* entry = findEntry(name);
  if (entry == nullptr) return fail(what + ": no controller of that name is loaded");
  const std::vector<TunablePid> tunables = entry->controller->tunablePids();
  controllers::Pid* pid = nullptr;
  std::string known;
  for (const TunablePid& tunable : tunables) {
    if (tunable.name == gains.pid) pid = tunable.pid;
    known += (known.empty() ? "'" : ", '") + tunable.name + "'";
  }
  if (pid == nullptr) {
    if (tunables.empty()) {
      return fail(what + ": a " + entry->type + " has no PID whose gains can be changed");
    }
    return fail(what + ": it has no PID '" + gains.pid + "'; its PIDs are " + known);
  }
  const controllers::Pid::Gains& g = gains.gains;
  if (const char* bad = firstNonFiniteGain(g); bad != nullptr) {
    return fail(what + ", PID '" + gains.pid + "': " + bad + " is not a finite number; give one");
  }
  if (g.i_min > 0.0 || g.i_max < 0.0) {
    return fail(fmt::format("{}, PID '{}': i_clamp_min {} and i_clamp_max {} must keep i_clamp_min <= 0 <= "
                            "i_clamp_max (control_toolbox's ranges)",
                            what, gains.pid, g.i_min, g.i_max));
  }
  pid->setGains(g);
  logger().info("controller '{}', PID '{}': gains set to p {}, i {}, d {}, i_clamp_min {}, i_clamp_max {}, "
                "antiwindup {}; taken at its next update",
                name, gains.pid, g.p_gain, g.i_gain, g.d_gain, g.i_min, g.i_max, g.antiwindup);
  return ServiceResult::success();
}

}  // namespace servoloop::controller_manager
