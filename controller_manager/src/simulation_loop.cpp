// SimulationLoop: lockstep with the physics, free-running or paced.
#include "servoloop/controller_manager/simulation_loop.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "servoloop/controller_manager/controller_manager.hpp"
#include "servoloop/controller_manager/loop_clock.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/step_grid.hpp"

namespace servoloop::controller_manager {

namespace {

constexpr double kRelativeTolerance = 1e-9;

// Two periods that should be the same, up to floating-point rounding.
bool samePeriod(double a_s, double b_s) {
  return std::abs(a_s - b_s) <= kRelativeTolerance * std::max(std::abs(a_s), std::abs(b_s));
}

Duration checkedPhysicsStep(const hardware_interface::SimulatedRobotHW& hw) {
  const double dt = hw.timeStep().seconds;
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    throw ConfigError(fmt::format(
        "SimulationLoop: the simulated hardware's physics time step is {} s; it must be a positive, "
        "finite time (check the world's time step setting)",
        dt));
  }
  return Duration(dt);
}

// The control period the options ask for, checked against the manager.
Duration chooseControlPeriod(const SimulationLoop::Options& options, const ControllerManager& manager,
                             Duration physics_step) {
  const double manager_rate_hz = manager.updateRate();
  const double requested_s = options.control_period.seconds;
  if (!std::isfinite(requested_s) || requested_s < 0.0) {
    throw ConfigError(fmt::format(
        "SimulationLoop: control_period {} s must be a positive time, or 0 to take the controller "
        "manager's update rate",
        requested_s));
  }
  if (requested_s == 0.0) {
    return manager_rate_hz > 0.0 ? Duration(1.0 / manager_rate_hz) : physics_step;
  }
  if (manager_rate_hz > 0.0 && !samePeriod(requested_s, 1.0 / manager_rate_hz)) {
    throw ConfigError(fmt::format(
        "SimulationLoop: control_period {} s ({} Hz) differs from the controller manager's update rate "
        "{} Hz, so per-controller rates would be wrong; give the manager update_rate {} Hz or leave "
        "control_period at 0",
        requested_s, 1.0 / requested_s, manager_rate_hz, 1.0 / requested_s));
  }
  return options.control_period;
}

// k with control_period = k * physics_step, or a ConfigError naming both.
std::uint64_t stepsPerUpdate(Duration control_period, Duration physics_step) {
  const double ratio = control_period.seconds / physics_step.seconds;
  const double k = std::round(ratio);
  if (k < 1.0 || !samePeriod(k * physics_step.seconds, control_period.seconds)) {
    const double below = std::max(1.0, std::floor(ratio)) * physics_step.seconds;
    const double above = std::max(1.0, std::ceil(ratio)) * physics_step.seconds;
    throw ConfigError(fmt::format(
        "SimulationLoop: control period {} s is not an integer multiple of the physics time step {} s "
        "(ratio {:.6g}); use a control period of {} s or {} s (controller manager update rate {:.6g} Hz "
        "or {:.6g} Hz), or change the physics time step",
        control_period.seconds, physics_step.seconds, ratio, below, above, 1.0 / below, 1.0 / above));
  }
  return static_cast<std::uint64_t>(k);
}

}  // namespace

SimulationLoop::SimulationLoop(hardware_interface::SimulatedRobotHW& hw, ControllerManager& manager,
                               Options options)
    : ControlLoop(hw, manager, options,
                  chooseControlPeriod(options, manager, checkedPhysicsStep(hw))),
      hw_(hw),
      physics_step_(checkedPhysicsStep(hw)),
      step_grid_(physics_step_.seconds),
      real_time_factor_(options.real_time_factor),
      max_catch_up_steps_(options.max_catch_up_steps) {
  steps_per_update_ = stepsPerUpdate(controlPeriod(), physics_step_);
  loop_clock::prepareCycleClock();  // calibrated here, not on the real-time thread
  if (!std::isfinite(real_time_factor_) || real_time_factor_ < 0.0) {
    throw ConfigError(fmt::format(
        "SimulationLoop: real_time_factor {} must be >= 0 (0 runs as fast as possible, 1 in real time)",
        real_time_factor_));
  }
}

void SimulationLoop::syncHardwareStep() noexcept {
  hardware_step_known_ = step_grid_.stepsAt(hw_.simTime().seconds, &hardware_step_);
}

void SimulationLoop::rewind() noexcept {
  steps_taken_.store(0, std::memory_order_release);
  last_update_step_ = 0;
  updated_before_ = false;
  syncHardwareStep();
}

ReturnType SimulationLoop::runCycle(bool* control_updated) noexcept {
  const std::uint64_t step = steps_taken_.load(std::memory_order_relaxed);
  // The hardware's steps × dt, on the decimal step grid so stamps read
  // 3.131, not 3.1310000000000002 (hardware_interface/step_grid.hpp): counted
  // here from the hardware's time at the start of the run, as each step()
  // advances it by one step; read from the hardware when it is off the grid.
  const Time time(hardware_step_known_ ? step_grid_.seconds(hardware_step_) : hw_.simTime().seconds);
  setBusTime(time);

  const ReturnType read_result = readHardware(time, physics_step_, step);

  *control_updated = !updated_before_ || step - last_update_step_ >= steps_per_update_;
  if (*control_updated) {
    // The control time since the previous update (nominal for the first one).
    const std::uint64_t steps_since = updated_before_ ? step - last_update_step_ : steps_per_update_;
    updateControllers(time, Duration(static_cast<double>(steps_since) * physics_step_.seconds));
    last_update_step_ = step;
    updated_before_ = true;
  }

  const ReturnType write_result = writeHardware(time, physics_step_, step);

  ReturnType step_result = ReturnType::error;
  beginHardwareCall(HardwareCall::step);
  try {
    step_result = hw_.step();
  } catch (...) {
    // step() must not throw; counted and reported as an error of step().
  }
  endHardwareCall();
  recordHardwareResult(HardwareCall::step, step_result, time, step);
  steps_taken_.store(step + 1, std::memory_order_release);
  if (step_result == ReturnType::ok) [[likely]] {
    ++hardware_step_;
  } else {
    syncHardwareStep();  // a failed step may or may not have advanced the time
  }
  finishCycle(time);

  // error wins over deactivate, deactivate over ok.
  if (read_result == ReturnType::error || write_result == ReturnType::error || step_result == ReturnType::error) {
    return ReturnType::error;
  }
  if (read_result == ReturnType::deactivate || write_result == ReturnType::deactivate ||
      step_result == ReturnType::deactivate) {
    return ReturnType::deactivate;
  }
  return ReturnType::ok;
}

void SimulationLoop::publishElapsed() noexcept {
  const double sim_time_s = step_grid_.seconds(steps_taken_.load(std::memory_order_relaxed));
  mutableStatistics().setElapsed(sim_time_s, wall_time_ns_);
}

ReturnType SimulationLoop::cycleOnce() noexcept {
  syncHardwareStep();
  mutableStatistics().beginUpdate();
  applyRequestedStatisticsReset();
  setPhaseTiming(true);
  sampleUpdateTiming();
  const std::int64_t start_ns = loop_clock::nowNs();
  bool control_updated = false;
  const ReturnType result = runCycle(&control_updated);
  const std::int64_t compute_ns = loop_clock::nowNs() - start_ns;
  mutableStatistics().recordCycle(compute_ns, control_updated);
  wall_time_ns_ += compute_ns;
  publishElapsed();
  mutableStatistics().endUpdate();
  return result;
}

void SimulationLoop::beginExternalRun() noexcept {
  syncHardwareStep();
  external_run_start_ns_ = loop_clock::cycleClockNs();
  external_wall_before_ns_ = wall_time_ns_;
  setPhaseTiming(false);
}

ReturnType SimulationLoop::externalCycle() noexcept {
  bool control_updated = false;
  if (free_cycles_++ % kFreeRunningTimingStride != 0) {
    const ReturnType result = runCycle(&control_updated);
    mutableStatistics().recordUntimedCycle(control_updated);
    return result;
  }
  applyRequestedStatisticsReset();
  setPhaseTiming(true);
  const std::int64_t start_ns = loop_clock::cycleClockNs();
  const ReturnType result = runCycle(&control_updated);
  const std::int64_t end_ns = loop_clock::cycleClockNs();
  setPhaseTiming(false);
  mutableStatistics().recordCycle(end_ns - start_ns, control_updated);
  wall_time_ns_ = external_wall_before_ns_ + (end_ns - external_run_start_ns_);
  publishElapsed();
  return result;
}

void SimulationLoop::endExternalRun() noexcept {
  wall_time_ns_ = external_wall_before_ns_ + (loop_clock::cycleClockNs() - external_run_start_ns_);
  publishElapsed();
  consumeStopRequest();
}

void SimulationLoop::runCycles(std::uint64_t max_cycles, const std::atomic<bool>* external_stop) {
  syncHardwareStep();
  if (real_time_factor_ > 0.0) {
    runPacedCycles(max_cycles, external_stop);
  } else {
    runFreeCycles(max_cycles, external_stop);
  }
  consumeStopRequest();
}

void SimulationLoop::runFreeCycles(std::uint64_t max_cycles, const std::atomic<bool>* external_stop) {
  // Nothing sleeps on the clock here, so the cheaper cycle clock times the
  // cycles (loop_clock.hpp), and only one cycle in kFreeRunningTimingStride
  // is timed: its two clock reads, the statistics and the elapsed times
  // then cost a few percent of a cheap cycle instead of a tenth of it.
  const std::int64_t run_start_ns = loop_clock::cycleClockNs();
  const std::int64_t wall_before_ns = wall_time_ns_;
  setPhaseTiming(false);
  for (std::uint64_t n = 0; n < max_cycles && !shouldStop(external_stop); ++n) {
    bool control_updated = false;
    // Counted across runs: a node runs its free loop in short runs.
    if (free_cycles_++ % kFreeRunningTimingStride != 0) {
      runCycle(&control_updated);
      mutableStatistics().recordUntimedCycle(control_updated);
      continue;
    }
    // No groups here (LoopStatistics::beginUpdate): one would open every
    // kFreeRunningTimingStride cycles, a few microseconds apart, and a reader
    // would hardly ever fit between two; the figures are read as they are.
    applyRequestedStatisticsReset();
    setPhaseTiming(true);
    const std::int64_t start_ns = loop_clock::cycleClockNs();
    runCycle(&control_updated);
    const std::int64_t end_ns = loop_clock::cycleClockNs();
    setPhaseTiming(false);  // the next kFreeRunningTimingStride - 1 cycles are not timed
    mutableStatistics().recordCycle(end_ns - start_ns, control_updated);
    wall_time_ns_ = wall_before_ns + (end_ns - run_start_ns);
    publishElapsed();
  }
  wall_time_ns_ = wall_before_ns + (loop_clock::cycleClockNs() - run_start_ns);
  publishElapsed();
}

void SimulationLoop::runPacedCycles(std::uint64_t max_cycles, const std::atomic<bool>* external_stop) {
  // Wall nanoseconds one physics step takes at the requested real-time factor.
  const double wall_per_step_ns = physics_step_.seconds / real_time_factor_ * 1e9;
  const auto max_lag_ns = static_cast<std::int64_t>(wall_per_step_ns * max_catch_up_steps_);

  const std::int64_t run_start_ns = loop_clock::nowNs();
  const std::int64_t wall_before_ns = wall_time_ns_;
  // The schedule: cycle n of this run ends no earlier than
  // anchor_ns + (n − anchor_cycle + 1) · wall_per_step_ns.
  std::int64_t anchor_ns = run_start_ns;
  std::uint64_t anchor_cycle = 0;

  // One clock read per cycle: the end of one cycle is the start of the next,
  // so a cycle's compute time includes the loop's own bookkeeping.
  std::int64_t cycle_start_ns = run_start_ns;
  setPhaseTiming(true);
  for (std::uint64_t n = 0; n < max_cycles && !shouldStop(external_stop); ++n) {
    bool control_updated = false;
    // The cycle's figures, its control time included, are one group, closed
    // before the sleep below (a snapshot waits for the work, not for the
    // pacing); the wall time the sleep adds is a group of its own.
    mutableStatistics().beginUpdate();
    applyRequestedStatisticsReset();
    sampleUpdateTiming();
    runCycle(&control_updated);
    std::int64_t end_ns = loop_clock::nowNs();
    mutableStatistics().recordCycle(end_ns - cycle_start_ns, control_updated);

    const std::int64_t deadline_ns =
        anchor_ns + std::llround(static_cast<double>(n - anchor_cycle + 1) * wall_per_step_ns);
    if (end_ns > deadline_ns) {
      mutableStatistics().recordOverrun();
      if (end_ns - deadline_ns > max_lag_ns) {
        // Too far behind to catch up: forget the backlog, restart from now.
        anchor_ns = end_ns;
        anchor_cycle = n + 1;
        mutableStatistics().recordScheduleReset();
      }
    }
    wall_time_ns_ = wall_before_ns + (end_ns - run_start_ns);
    publishElapsed();
    mutableStatistics().endUpdate();
    if (end_ns <= deadline_ns) {
      loop_clock::sleepUntilNs(deadline_ns);
      end_ns = loop_clock::nowNs();
      wall_time_ns_ = wall_before_ns + (end_ns - run_start_ns);
      mutableStatistics().beginUpdate();
      publishElapsed();
      mutableStatistics().endUpdate();
    }
    cycle_start_ns = end_ns;
  }
}

void SimulationLoop::run(const std::atomic<bool>& stop_requested) {
  runCycles(std::numeric_limits<std::uint64_t>::max(), &stop_requested);
}

void SimulationLoop::runFor(Duration sim_time) {
  const double steps = sim_time.seconds / physics_step_.seconds;
  if (!std::isfinite(steps) || steps < 0.0) {
    throw Error(fmt::format("SimulationLoop::runFor: simulated time {} s must be >= 0 and finite",
                            sim_time.seconds));
  }
  runCycles(static_cast<std::uint64_t>(std::ceil(steps - 1e-9)), nullptr);
}

}  // namespace servoloop::controller_manager
