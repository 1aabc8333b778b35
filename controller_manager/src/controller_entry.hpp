#pragma once
// The manager's record of one loaded controller (internal to the manager).
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "servoloop/controller_manager/controller_factory.hpp"
#include "servoloop/controller_manager/controller_manager.hpp"
#include "servoloop/controller_manager/controller_spec.hpp"
#include "servoloop/hardware_interface/controller_info.hpp"
#include "servoloop/core/time.hpp"

namespace servoloop::controller_manager::detail {

// One contained fault, written by the real-time thread and published through
// `pending`; the non-real-time side reads it once `pending` is seen set and
// clears `pending` after. The real-time thread writes a record only while
// `pending` is clear, so the two sides never touch the fields at once.
struct FaultRecord {
  FaultKind kind = FaultKind::update_threw;
  std::array<char, 256> what{};  // exception message, truncated; "" if none
  std::size_t command_index = ControllerBase::kAllCommandsFinite;
  double command_value = 0.0;
  bool fallbacks_started = false;  // its fallback controllers were started
  std::atomic<bool> pending{false};

  // Real-time. Allocation-free; a second fault before the first was drained is
  // dropped (the first one is what stopped the controller).
  void publish(FaultKind fault_kind, const char* message, std::size_t index = ControllerBase::kAllCommandsFinite,
               double value = 0.0, bool started_fallbacks = false) noexcept;
};

struct alignas(64) ControllerEntry {
  // What every cycle reads first, on one cache line: the controller, and the
  // real-time thread's schedule of it.
  ControllerPtr controller;
  // The manager cycle of the next update(): the cycle in which starting() ran
  // plus k·rate.divisor (real-time thread only).
  std::uint64_t next_update_cycle = 0;
  Time last_update_time;  // control time of starting() or the last update() (real-time thread only)
  UpdateRateChoice rate;

  std::string name;
  std::string type;
  hardware_interface::ControllerInfo info;  // name, type and claims, for the hardware
  // Started when this controller faults in update(); loaded before it, each
  // claiming only what it claims. Fixed at load (the real-time thread reads it).
  std::vector<ControllerEntry*> fallbacks;
  bool stopped_by_hardware_failure = false;  // scratch of containHardwareFailure (real-time thread)

  FaultRecord fault;
  DurationStatistics update_time;  // written by the real-time thread (timed cycles)
  std::string last_fault;  // non-real-time: the last drained fault's message
  FaultKind last_fault_kind = FaultKind::update_threw;  // non-real-time: its kind
};

}  // namespace servoloop::controller_manager::detail
