// ControllerManager: the real-time cycle. Everything here runs on the control
// loop's thread: no allocation, no locks, no logging, nothing thrown out of it.
// Faults are written to preallocated records that processFaults() reports.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>

#include "asymmetric_fence.hpp"
#include "controller_entry.hpp"
#include "servoloop/controller_manager/controller_manager.hpp"
#include "servoloop/controller_manager/loop_clock.hpp"

namespace servoloop::controller_manager {

UpdateRateChoice chooseUpdateRate(double manager_rate_hz, double requested_rate_hz) {
  if (!(manager_rate_hz > 0.0)) {
    // No fixed manager rate: every controller updates every cycle.
    return UpdateRateChoice{1, 0.0, !(requested_rate_hz > 0.0)};
  }
  if (!(requested_rate_hz > 0.0)) return UpdateRateChoice{1, manager_rate_hz, true};
  const double ratio = manager_rate_hz / requested_rate_hz;
  if (ratio <= 1.0) {
    return UpdateRateChoice{1, manager_rate_hz, std::abs(ratio - 1.0) < 1e-9};
  }
  const double nearest = std::round(ratio);
  if (std::abs(ratio - nearest) < 1e-9 * ratio) {
    const auto divisor = static_cast<std::uint32_t>(nearest);
    return UpdateRateChoice{divisor, manager_rate_hz / divisor, true};
  }
  // The achievable rates are manager/k; the nearest one to the request is at
  // k = floor(ratio) or k = ceil(ratio).
  const double below = std::floor(ratio);
  const double above = std::ceil(ratio);
  const double error_below = std::abs(manager_rate_hz / below - requested_rate_hz);
  const double error_above = std::abs(manager_rate_hz / above - requested_rate_hz);
  const auto divisor = static_cast<std::uint32_t>(error_below <= error_above ? below : above);
  return UpdateRateChoice{divisor, manager_rate_hz / divisor, false};
}

namespace detail {
void FaultRecord::publish(FaultKind fault_kind, const char* message, std::size_t index, double value,
                          bool started_fallbacks) noexcept {
  if (pending.load(std::memory_order_acquire)) return;
  kind = fault_kind;
  what.fill('\0');
  if (message != nullptr) std::strncpy(what.data(), message, what.size() - 1);
  command_index = index;
  command_value = value;
  fallbacks_started = started_fallbacks;
  pending.store(true, std::memory_order_release);
}
}  // namespace detail

void ControllerManager::contain(detail::ControllerEntry& entry, FaultKind kind,
                                const char* what) noexcept {
  entry.controller->abortRequest();
  entry.fault.publish(kind, what);
}

bool ControllerManager::startNow(detail::ControllerEntry& entry, const Time& time) noexcept {
  entry.next_update_cycle = cycle_ + entry.rate.divisor;
  entry.last_update_time = time;
  try {
    entry.controller->startRequest(time);
  } catch (const std::exception& e) {
    contain(entry, FaultKind::starting_threw, e.what());
    return false;
  } catch (...) {
    contain(entry, FaultKind::starting_threw, "an exception not derived from std::exception");
    return false;
  }
  const std::size_t bad = entry.controller->firstNonFiniteCommand();
  if (bad != ControllerBase::kAllCommandsFinite) {
    const double value = *entry.controller->claimedCommands()[bad].command;
    entry.controller->abortRequest();
    entry.fault.publish(FaultKind::non_finite_command, "", bad, value);
    return false;
  }
  return true;
}

void ControllerManager::containInUpdate(detail::ControllerEntry& entry, FaultKind kind, const char* what,
                                        const Time& time, std::size_t command_index, double value) noexcept {
  entry.controller->abortRequest();
  bool started = false;
  if (!entry.fallbacks.empty()) {
    // Odd while fallbacks start, even again after: a switch is prepared only
    // at an even count, and one prepared before this is not carried out.
    fallback_starts_.fetch_add(1, std::memory_order_acq_rel);
    for (detail::ControllerEntry* fallback : entry.fallbacks) {
      if (fallback->controller->isRunning()) continue;
      started = startNow(*fallback, time) || started;
    }
    fallback_starts_.fetch_add(1, std::memory_order_acq_rel);
  }
  entry.fault.publish(kind, what, command_index, value, started);
}

int ControllerManager::enterRealtimeList() noexcept {
  // Announce which list this cycle reads, then re-check it is still the
  // current one: a publisher that swapped in between sees the announcement
  // and waits, or we see its swap and announce the new list. Between the
  // announcement and the re-check: a full fence, or a compiler barrier that
  // the publisher's heavy fence completes (asymmetric_fence.hpp).
  int index = realtime_current_list_.load(std::memory_order_acquire);
  for (;;) {
    if (asymmetric_list_fence_) {
      realtime_reading_list_.store(index, std::memory_order_relaxed);
      asymmetric_fence::light();
    } else {
      realtime_reading_list_.store(index);
    }
    const int again = realtime_current_list_.load();
    if (again == index) return index;
    index = again;
  }
}

void ControllerManager::update(const Time& time, const Duration& /*period*/) noexcept {
  ++cycle_;
  SwitchPhase expected = SwitchPhase::pending;
  if (switch_phase_.load(std::memory_order_acquire) == SwitchPhase::pending &&
      switch_phase_.compare_exchange_strong(expected, SwitchPhase::executing,
                                            std::memory_order_acq_rel)) {
    executeSwitch(time);
    switch_phase_.store(SwitchPhase::done, std::memory_order_release);
  }

  const std::vector<detail::ControllerEntry*>& list = realtime_lists_[enterRealtimeList()];
  if (update_timing_reset_.load(std::memory_order_acquire)) [[unlikely]] {
    for (detail::ControllerEntry* entry : list) entry->update_time.reset();
    update_timing_reset_.store(false, std::memory_order_release);
  }
  // Timed cycles read the clock once here and once after each update: a
  // controller's time runs from the previous reading, so it includes the
  // manager's few checks after the update before it (the controllers that did
  // not run, the finite-command check). A fault's handling is read past, so it
  // is nobody's update time.
  std::int64_t clock_ns = 0;
  if (time_updates_) [[unlikely]] {
    clock_ns = loop_clock::cycleClockNs();
    for (detail::ControllerEntry* entry : list) updateController<true>(*entry, time, clock_ns);
  } else {
    for (detail::ControllerEntry* entry : list) updateController<false>(*entry, time, clock_ns);
  }
  // Release is enough here: a publisher waiting for this list sees the -1
  // only after every read of the list above.
  realtime_reading_list_.store(-1, std::memory_order_release);
}

std::size_t ControllerManager::containHardwareFailure(const Time& time, const char* why) noexcept {
  std::size_t stopped = 0;
  const int list_index = enterRealtimeList();
  const auto& list = realtime_lists_[list_index];
  // Stop them all first, then start fallbacks: a fallback started for one
  // controller must not be taken for a controller that was running.
  for (detail::ControllerEntry* entry : list) {
    entry->stopped_by_hardware_failure =
        entry->controller->isRunning() && !entry->controller->claimedCommands().empty();
    if (entry->stopped_by_hardware_failure) {
      entry->controller->abortRequest();
      ++stopped;
    }
  }
  // The epoch moves on even when nothing was running: a switch prepared
  // before the stop (one that would start a controller now, in this cycle's
  // update) is then not carried out.
  fallback_starts_.fetch_add(1, std::memory_order_acq_rel);  // odd: see containInUpdate
  for (detail::ControllerEntry* entry : list) {
    if (!entry->stopped_by_hardware_failure) continue;
    entry->stopped_by_hardware_failure = false;
    bool started = false;
    for (detail::ControllerEntry* fallback : entry->fallbacks) {
      if (fallback->controller->isRunning()) continue;
      started = startNow(*fallback, time) || started;
    }
    entry->fault.publish(FaultKind::hardware_failed, why, ControllerBase::kAllCommandsFinite, 0.0, started);
  }
  fallback_starts_.fetch_add(1, std::memory_order_acq_rel);
  realtime_reading_list_.store(-1, std::memory_order_release);
  return stopped;
}

void ControllerManager::executeSwitch(const Time& time) noexcept {
  if (fallback_starts_.load(std::memory_order_acquire) != switch_plan_.fallback_epoch) {
    switch_plan_.aborted = true;  // a fallback took over since the plan was made
    return;
  }
  // The hardware's mode switch first: when it cannot carry it out, nothing
  // changes (no controller stops or starts) and the request fails.
  // Why it failed is copied into the plan without allocating, an exception's
  // message inside its catch block (it dies with the exception).
  char* why = switch_plan_.hardware_error.data();
  const std::size_t why_size = switch_plan_.hardware_error.size();
  std::snprintf(why, why_size, "%s", "returned an error");
  ReturnType modes = ReturnType::error;
  try {
    modes = robot_hw_->doSwitch(switch_plan_.start_infos, switch_plan_.stop_infos);
  } catch (const std::exception& e) {
    std::snprintf(why, why_size, "threw: %s", e.what());
  } catch (...) {
    std::snprintf(why, why_size, "%s", "threw an exception not derived from std::exception");
  }
  if (modes != ReturnType::ok) {
    switch_plan_.hardware_refused = true;
    return;
  }
  // Then the stop list.
  for (detail::ControllerEntry* entry : switch_plan_.stop) {
    try {
      entry->controller->stopRequest(time);
    } catch (const std::exception& e) {
      contain(*entry, FaultKind::stopping_threw, e.what());
    } catch (...) {
      contain(*entry, FaultKind::stopping_threw, "an exception not derived from std::exception");
    }
  }
  // Then the start list. Their first update comes in the next cycle.
  for (std::size_t i = 0; i < switch_plan_.start.size(); ++i) {
    switch_plan_.start_failed[i] = startNow(*switch_plan_.start[i], time) ? 0 : 1;
  }
}

template <bool kTimed>
inline void ControllerManager::updateController(detail::ControllerEntry& entry, const Time& time,
                                                std::int64_t& clock_ns) noexcept {
  ControllerBase& controller = *entry.controller;
  // Every rate.divisor-th cycle after the one that started it (a comparison
  // rather than a modulo: this runs for every controller in every cycle).
  if (!controller.isRunning() || cycle_ < entry.next_update_cycle) return;
  entry.next_update_cycle = cycle_ + entry.rate.divisor;

  const Duration period = time - entry.last_update_time;
  entry.last_update_time = time;
  ReturnType result = ReturnType::ok;
  try {
    result = controller.updateRequest(time, period);
  } catch (const std::exception& e) {
    containInUpdate(entry, FaultKind::update_threw, e.what(), time);
    if constexpr (kTimed) clock_ns = loop_clock::cycleClockNs();
    return;
  } catch (...) {
    containInUpdate(entry, FaultKind::update_threw, "an exception not derived from std::exception", time);
    if constexpr (kTimed) clock_ns = loop_clock::cycleClockNs();
    return;
  }
  if constexpr (kTimed) {
    const std::int64_t now_ns = loop_clock::cycleClockNs();
    entry.update_time.record(now_ns - clock_ns);
    clock_ns = now_ns;
  }
  if (result == ReturnType::ok && controller.firstNonFiniteCommand() == ControllerBase::kAllCommandsFinite) [[likely]] {
    return;
  }
  if (handleUpdateResult(entry, result, time)) {
    if constexpr (kTimed) clock_ns = loop_clock::cycleClockNs();
  }
}

bool ControllerManager::handleUpdateResult(detail::ControllerEntry& entry, ReturnType result,
                                           const Time& time) noexcept {
  ControllerBase& controller = *entry.controller;
  switch (result) {
    case ReturnType::ok: {
      const std::size_t bad = controller.firstNonFiniteCommand();
      if (bad == ControllerBase::kAllCommandsFinite) return false;
      containInUpdate(entry, FaultKind::non_finite_command, "", time, bad, *controller.claimedCommands()[bad].command);
      return true;
    }
    case ReturnType::error:
      containInUpdate(entry, FaultKind::update_returned_error, "", time);
      return true;
    case ReturnType::deactivate:
      try {
        controller.stopRequest(time);
      } catch (const std::exception& e) {
        contain(entry, FaultKind::stopping_threw, e.what());
      } catch (...) {
        contain(entry, FaultKind::stopping_threw, "an exception not derived from std::exception");
      }
      return true;
  }
  return false;
}

}  // namespace servoloop::controller_manager
