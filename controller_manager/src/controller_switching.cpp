// ControllerManager: validating a controller switch and handing it to the
// real-time thread (non-real-time side). The real-time side is
// ControllerManager::executeSwitch in controller_scheduling.cpp.
#include <algorithm>
#include <chrono>
#include <map>
#include <thread>

#include "controller_entry.hpp"
#include "servoloop/controller_manager/controller_manager.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::controller_manager {

namespace {
bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string joinNames(const std::vector<detail::ControllerEntry*>& entries) {
  std::string joined;
  for (const auto* entry : entries) joined += (joined.empty() ? "" : ", ") + entry->name;
  return joined.empty() ? "none" : joined;
}

// Names the resources that more than one controller of `running` claims.
std::string describeConflicts(const std::vector<hardware_interface::ControllerInfo>& running) {
  std::map<std::string, std::vector<std::string>> claimers;
  for (const auto& controller : running) {
    for (const auto& claimed : controller.claimed_resources) {
      for (const auto& resource : claimed.resources) {
        auto& names = claimers[resource];
        if (std::find(names.begin(), names.end(), controller.name) == names.end()) {
          names.push_back(controller.name);
        }
      }
    }
  }
  std::string text;
  for (const auto& [resource, names] : claimers) {
    if (names.size() < 2) continue;
    std::string who;
    for (const auto& name : names) who += (who.empty() ? "'" : "' and '") + name;
    text += (text.empty() ? "" : "; ") + std::string("'") + resource + "' is claimed by " + who + "'";
  }
  return text.empty() ? "the hardware reports a resource conflict" : text;
}
}  // namespace

ServiceResult ControllerManager::switchController(const std::vector<std::string>& start_controllers,
                                                  const std::vector<std::string>& stop_controllers,
                                                  SwitchStrictness strictness, bool start_asap,
                                                  double timeout_s) {
  return switchController(
      SwitchRequest{start_controllers, stop_controllers, strictness, start_asap, timeout_s});
}

ServiceResult ControllerManager::switchController(const SwitchRequest& request) {
  std::lock_guard<std::mutex> lock(services_mutex_);
  processFaultsLocked();
  bool nothing_to_do = false;
  ServiceResult prepared = prepareSwitchLocked(request, &nothing_to_do);
  if (!prepared || nothing_to_do) return prepared;
  return waitForSwitchLocked(request.timeout_s);
}

void ControllerManager::setSwitchGuard(SwitchGuard guard) {
  std::lock_guard<std::mutex> lock(services_mutex_);
  switch_guard_ = std::move(guard);
}

ServiceResult ControllerManager::requestSwitch(const SwitchRequest& request) {
  std::lock_guard<std::mutex> lock(services_mutex_);
  processFaultsLocked();
  bool nothing_to_do = false;
  return prepareSwitchLocked(request, &nothing_to_do);
}

bool ControllerManager::switchPending() const {
  const SwitchPhase phase = switch_phase_.load();
  return phase == SwitchPhase::pending || phase == SwitchPhase::executing;
}

ServiceResult ControllerManager::finishSwitch() {
  std::lock_guard<std::mutex> lock(services_mutex_);
  if (switch_phase_.load(std::memory_order_acquire) != SwitchPhase::done) return ServiceResult::success();
  return completeSwitchLocked(/*announce=*/false);
}

void ControllerManager::finishDoneSwitchLocked() {
  if (switch_phase_.load(std::memory_order_acquire) == SwitchPhase::done) {
    completeSwitchLocked(/*announce=*/false);  // a failure is logged
  }
}

ServiceResult ControllerManager::prepareSwitchLocked(const SwitchRequest& request,
                                                     bool* nothing_to_do) {
  *nothing_to_do = false;
  finishDoneSwitchLocked();
  if (switch_phase_.load() != SwitchPhase::idle) {
    return fail("switch controllers: an earlier switch is still waiting for the real-time thread");
  }
  // The states read below are those after any fallback start the real-time
  // thread is in the middle of (an odd count; it takes one cycle at most).
  std::uint64_t fallback_epoch = fallback_starts_.load(std::memory_order_acquire);
  while (fallback_epoch % 2 != 0) {
    std::this_thread::yield();
    fallback_epoch = fallback_starts_.load(std::memory_order_acquire);
  }
  // Asked only now: a stop the guard does not see yet moves the epoch read
  // above, and the real-time thread then drops the plan (executeSwitch).
  if (switch_guard_) {
    const std::string refused = switch_guard_(request);
    if (!refused.empty()) return fail(refused);
  }
  for (const auto& name : request.start_controllers) {
    if (contains(request.stop_controllers, name)) {
      return fail("switch controllers: controller '" + name +
                  "' is in both the start and the stop list; name it in one of them only");
    }
  }
  const bool strict = request.strictness == SwitchStrictness::STRICT;

  // Check each name; BEST_EFFORT drops what STRICT refuses.
  std::vector<detail::ControllerEntry*> stop;
  for (const auto& name : request.stop_controllers) {
    detail::ControllerEntry* entry = findEntry(name);
    std::string problem;
    if (entry == nullptr) {
      problem = "could not stop controller '" + name + "': no controller of that name is loaded";
    } else if (!entry->controller->isRunning()) {
      problem = "could not stop controller '" + name + "': it is not running (it is " +
                toString(entry->controller->state()) + ")";
    }
    if (!problem.empty()) {
      if (strict) return fail("switch controllers (STRICT): " + problem);
      logger().debug("switch controllers (BEST_EFFORT): {}; dropped", problem);
      continue;
    }
    if (std::find(stop.begin(), stop.end(), entry) == stop.end()) stop.push_back(entry);
  }
  std::vector<detail::ControllerEntry*> start;
  for (const auto& name : request.start_controllers) {
    detail::ControllerEntry* entry = findEntry(name);
    std::string problem;
    if (entry == nullptr) {
      problem = "could not start controller '" + name + "': no controller of that name is loaded";
    } else if (entry->controller->isRunning()) {
      problem = "could not start controller '" + name + "': it is already running";
    }
    if (!problem.empty()) {
      if (strict) return fail("switch controllers (STRICT): " + problem);
      logger().debug("switch controllers (BEST_EFFORT): {}; dropped", problem);
      continue;
    }
    if (std::find(start.begin(), start.end(), entry) == start.end()) start.push_back(entry);
  }
  if (start.empty() && stop.empty()) {
    *nothing_to_do = true;
    return ServiceResult::success();
  }

  // Resource conflicts among the controllers that would run afterwards.
  std::vector<hardware_interface::ControllerInfo> running_after;
  for (const auto& entry : entries_) {
    const bool stays = entry->controller->isRunning() &&
                       std::find(stop.begin(), stop.end(), entry.get()) == stop.end();
    if (stays) running_after.push_back(entry->info);
  }
  for (const auto* entry : start) running_after.push_back(entry->info);
  if (robot_hw_->checkForConflict(running_after)) {
    return fail("switch controllers: starting " + joinNames(start) +
                " would conflict: " + describeConflicts(running_after) +
                "; stop the other controller in the same switch");
  }

  std::vector<hardware_interface::ControllerInfo> start_infos;
  std::vector<hardware_interface::ControllerInfo> stop_infos;
  for (const auto* entry : start) start_infos.push_back(entry->info);
  for (const auto* entry : stop) stop_infos.push_back(entry->info);
  try {
    if (!robot_hw_->prepareSwitch(start_infos, stop_infos)) {
      return fail("switch controllers: the hardware refused the switch (prepareSwitch) of start [" +
                  joinNames(start) + "], stop [" + joinNames(stop) + "]");
    }
  } catch (const std::exception& e) {
    return fail(std::string("switch controllers: the hardware's prepareSwitch failed: ") + e.what());
  }

  // Hand it over; the real-time thread reads the plan only once it sees `pending`.
  switch_plan_.stop = std::move(stop);
  switch_plan_.start = std::move(start);
  switch_plan_.start_infos = std::move(start_infos);
  switch_plan_.stop_infos = std::move(stop_infos);
  switch_plan_.start_failed.assign(switch_plan_.start.size(), 0);
  switch_plan_.fallback_epoch = fallback_epoch;
  switch_plan_.aborted = false;
  switch_plan_.hardware_refused = false;
  switch_phase_.store(SwitchPhase::pending, std::memory_order_release);
  return ServiceResult::success();
}

ServiceResult ControllerManager::waitForSwitchLocked(double timeout_s) {
  const auto begin = std::chrono::steady_clock::now();
  const auto timeout = std::chrono::duration<double>(timeout_s);
  while (switch_phase_.load(std::memory_order_acquire) != SwitchPhase::done) {
    if (timeout_s > 0.0 && std::chrono::steady_clock::now() - begin >= timeout) {
      SwitchPhase expected = SwitchPhase::pending;
      if (switch_phase_.compare_exchange_strong(expected, SwitchPhase::idle)) {
        return fail("switch controllers: the real-time thread did not carry the switch out within " +
                    std::to_string(timeout_s) +
                    " s (is the control loop running?); nothing was switched");
      }
      // The real-time thread has it in hand: carrying it out never blocks, so wait on.
    }
    std::this_thread::sleep_for(std::chrono::microseconds(100));
  }
  return completeSwitchLocked(/*announce=*/true);
}

ServiceResult ControllerManager::completeSwitchLocked(bool announce) {
  if (switch_plan_.hardware_refused) {
    const std::string why = switch_plan_.hardware_error.data();
    switch_phase_.store(SwitchPhase::idle);
    return fail("switch controllers: the hardware could not change its command modes for start [" +
                joinNames(switch_plan_.start) + "], stop [" + joinNames(switch_plan_.stop) + "] (RobotHW::doSwitch " +
                why + "); nothing was switched: the running controllers run on");
  }
  const std::vector<ControllerFault> faults = processFaultsLocked();
  if (switch_plan_.aborted) {
    switch_phase_.store(SwitchPhase::idle);
    std::string which;
    for (const ControllerFault& fault : faults) which += (which.empty() ? "" : ", ") + fault.controller;
    return fail("switch controllers: " +
                (which.empty() ? std::string("the hardware failed (protective stop or fault)")
                               : "a controller faulted (" + which + ")") +
                " while the switch was being prepared (fallback controllers, if any, started), so nothing was "
                "switched; check `control list` and `control safety`, and retry");
  }
  std::string failed_to_start;
  for (std::size_t i = 0; i < switch_plan_.start.size(); ++i) {
    if (switch_plan_.start_failed[i] == 0) continue;
    const detail::ControllerEntry* entry = switch_plan_.start[i];
    failed_to_start += (failed_to_start.empty() ? "" : "; ") + entry->last_fault;
  }
  if (announce) {
    logger().info("switched controllers: started [{}], stopped [{}]", joinNames(switch_plan_.start),
                  joinNames(switch_plan_.stop));
  }
  switch_phase_.store(SwitchPhase::idle);
  if (!failed_to_start.empty()) {
    return fail("switch controllers: the switch was carried out, but " + failed_to_start);
  }
  return ServiceResult::success();
}

}  // namespace servoloop::controller_manager
