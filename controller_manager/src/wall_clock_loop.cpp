// WallClockLoop: fixed-rate cycles on absolute monotonic deadlines.
#include "servoloop/controller_manager/wall_clock_loop.hpp"

#include <sys/prctl.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "servoloop/controller_manager/controller_manager.hpp"
#include "servoloop/controller_manager/loop_clock.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::controller_manager {

namespace {

constexpr double kNsPerSecond = 1e9;

Duration chooseWallPeriod(const WallClockLoop::Options& options, const ControllerManager& manager) {
  const double manager_rate_hz = manager.updateRate();
  const double requested_s = options.period.seconds;
  if (!std::isfinite(requested_s) || requested_s < 0.0) {
    throw ConfigError(fmt::format(
        "WallClockLoop: period {} s must be a positive time, or 0 to take the controller manager's "
        "update rate",
        requested_s));
  }
  if (requested_s == 0.0) {
    if (!(manager_rate_hz > 0.0)) {
      throw ConfigError(
          "WallClockLoop: no cycle period: the controller manager has no update rate and "
          "WallClockLoop::Options::period is 0; set the manager's update_rate (e.g. 1000 Hz)");
    }
    return Duration(1.0 / manager_rate_hz);
  }
  if (manager_rate_hz > 0.0 && std::abs(requested_s * manager_rate_hz - 1.0) > 1e-9) {
    throw ConfigError(fmt::format(
        "WallClockLoop: period {} s ({} Hz) differs from the controller manager's update rate {} Hz, "
        "so per-controller rates would be wrong; give the manager update_rate {} Hz or leave period at 0",
        requested_s, 1.0 / requested_s, manager_rate_hz, 1.0 / requested_s));
  }
  if (requested_s < 1e-6) {
    throw ConfigError(fmt::format("WallClockLoop: period {} s is below the 1 us the loop can keep",
                                  requested_s));
  }
  return options.period;
}

}  // namespace

WallClockLoop::WallClockLoop(hardware_interface::RobotHW& hw, ControllerManager& manager, Options options)
    : ControlLoop(hw, manager, options, chooseWallPeriod(options, manager)),
      period_ns_(std::llround(controlPeriod().seconds * kNsPerSecond)),
      simulated_(options.step_simulation ? dynamic_cast<hardware_interface::SimulatedRobotHW*>(&hw) : nullptr) {
  if (simulated_ != nullptr && std::abs(simulated_->timeStep().seconds - controlPeriod().seconds) >
                                   1e-9 * controlPeriod().seconds) {
    throw ConfigError(fmt::format(
        "WallClockLoop: a simulated robot on the wall clock is stepped once per cycle, but its time step {} s "
        "is not the cycle period {} s; set the time step to 1 / the update rate ({} Hz)",
        simulated_->timeStep().seconds, controlPeriod().seconds, 1.0 / controlPeriod().seconds));
  }
}

void WallClockLoop::runCycles(std::int64_t run_length_ns, const std::atomic<bool>* external_stop) {
  // A thread of the normal scheduler sleeps up to its timer slack (50 us by
  // default) past each deadline; 1 ns makes the kernel wake it on time, as a
  // SCHED_FIFO thread is. The calling thread is the loop's own.
  prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  const std::int64_t run_start_ns = loop_clock::nowNs();
  // The loop keeps one deadline grid from its first run's start (the origin):
  // control time is how far along it the loop is, so its next deadline is
  // origin + control time. A run that follows one which ran its length
  // carries on from there (a node runs the loop in pieces between timed
  // publications); so does a run after a stop (a fault, until `control
  // recover`): control time stays the time since the origin, as the
  // controllers' time is.
  if (origin_ns_ < 0) origin_ns_ = run_start_ns;
  std::int64_t deadline_ns = origin_ns_ + control_time_ns_;
  // The run covers the grid from there for its length, so pieces run one
  // after another cover it once: a piece that ends where the control time
  // says the next publication is due ends on that deadline.
  std::int64_t run_end_ns = run_length_ns == std::numeric_limits<std::int64_t>::max()
                                ? run_length_ns
                                : deadline_ns + run_length_ns;
  // Wall time goes on across the pause (or the stop) too, as the control time does.
  const std::int64_t wall_before_ns = wall_time_ns_ + (grid_.last_end_ns >= 0 ? run_start_ns - grid_.last_end_ns : 0);
  wall_time_ns_ = wall_before_ns;  // up to date at run_start_ns
  if (run_start_ns > deadline_ns) {
    // Deadlines passed while no run ran: a pause between two runs missed
    // them (an overrun), or the loop stood stopped (skipped, not an overrun).
    // Skipped as below, the next cycle at the first deadline ahead; they
    // count towards the length, so a run they swallowed whole still runs its
    // one cycle, late (a node's run up to a publication that fell due in a
    // stop runs one cycle and ends, and the publication goes out).
    const std::int64_t missed = (run_start_ns - deadline_ns) / period_ns_ + 1;
    deadline_ns += missed * period_ns_;
    control_time_ns_ += missed * period_ns_;
    mutableStatistics().beginUpdate();
    if (grid_.continues) {
      mutableStatistics().recordOverrun(static_cast<std::uint64_t>(missed));
    } else {
      mutableStatistics().recordSkippedDeadlines(static_cast<std::uint64_t>(missed));
    }
    mutableStatistics().setElapsed(static_cast<double>(control_time_ns_) / kNsPerSecond, wall_before_ns);
    mutableStatistics().endUpdate();
    if (run_length_ns > 0) run_end_ns = std::max(run_end_ns, deadline_ns + 1);
  }
  std::int64_t previous_start_ns = grid_.previous_start_ns;
  std::int64_t previous_deadline_ns = grid_.previous_deadline_ns;
  std::int64_t last_end_ns = run_start_ns;

  while (deadline_ns < run_end_ns && !shouldStop(external_stop)) {
    loop_clock::sleepUntilNs(deadline_ns);
    const std::int64_t start_ns = loop_clock::nowNs();
    // The cycle's figures, from here to its elapsed times, are one group.
    mutableStatistics().beginUpdate();
    applyRequestedStatisticsReset();
    sampleUpdateTiming();
    mutableStatistics().recordWakeupLatency(start_ns - deadline_ns);
    if (previous_start_ns >= 0) {
      // Against the grid: after skipped deadlines the period is a multiple.
      const std::int64_t off_ns = (start_ns - previous_start_ns) - (deadline_ns - previous_deadline_ns);
      mutableStatistics().recordPeriodJitter(off_ns < 0 ? -off_ns : off_ns);
    }
    previous_deadline_ns = deadline_ns;
    const Time time(static_cast<double>(start_ns - origin_ns_) / kNsPerSecond);
    const Duration period(previous_start_ns < 0 ? controlPeriod().seconds
                                                : static_cast<double>(start_ns - previous_start_ns) / kNsPerSecond);
    previous_start_ns = start_ns;

    setBusTime(time);
    readHardware(time, period, cycles_);
    updateControllers(time, period);
    writeHardware(time, period, cycles_);
    if (simulated_ != nullptr) {
      ReturnType stepped = ReturnType::error;
      try {
        stepped = simulated_->step();
      } catch (...) {
        // step() must not throw; counted and reported as an error of step().
      }
      recordHardwareResult(HardwareCall::step, stepped, time, cycles_);
    }
    finishCycle(time);
    ++cycles_;

    const std::int64_t end_ns = loop_clock::nowNs();
    mutableStatistics().recordCycle(end_ns - start_ns, true);
    std::int64_t advance_ns = period_ns_;
    if (end_ns > deadline_ns + period_ns_) {
      // Skip the deadlines already missed: the next cycle starts at the first
      // one still ahead, on the original grid.
      const std::int64_t missed = (end_ns - deadline_ns - period_ns_) / period_ns_ + 1;
      mutableStatistics().recordOverrun(static_cast<std::uint64_t>(missed));
      advance_ns += missed * period_ns_;
    }
    deadline_ns += advance_ns;
    control_time_ns_ += advance_ns;
    last_end_ns = end_ns;
    wall_time_ns_ = wall_before_ns + (end_ns - run_start_ns);
    mutableStatistics().setElapsed(static_cast<double>(control_time_ns_) / kNsPerSecond, wall_time_ns_);
    mutableStatistics().endUpdate();
  }
  if (shouldStop(external_stop)) {
    // Stopped (or the hardware stopped it): the next run resumes the grid at
    // a deadline of its own, and counts the wall time from here.
    grid_ = Grid{};
    grid_.last_end_ns = last_end_ns;
  } else {
    grid_ = Grid{true, previous_start_ns, previous_deadline_ns, last_end_ns};
  }
  consumeStopRequest();
}

void WallClockLoop::run(const std::atomic<bool>& stop_requested) {
  runCycles(std::numeric_limits<std::int64_t>::max(), &stop_requested);
}

void WallClockLoop::runFor(Duration wall_time) {
  if (!std::isfinite(wall_time.seconds) || wall_time.seconds < 0.0) {
    throw Error(fmt::format("WallClockLoop::runFor: wall time {} s must be >= 0 and finite", wall_time.seconds));
  }
  runCycles(std::llround(wall_time.seconds * kNsPerSecond), nullptr);
}

}  // namespace servoloop::controller_manager
