#pragma once
// The control loop for real hardware: cycles at a fixed period on the
// monotonic clock, each one
//
//   t = monotonic time since the first deadline of the loop's first run (the
//       run's start: the first cycle reads its wake-up latency)
//   hw.read(t, period)  →  manager.update(t, period), cycle hook  →  hw.write(t, period)
//   (→ hw.step() for a simulated robot standing in for hardware, see below)
//
// where period is the wall time since the previous cycle started (the nominal
// period for the first cycle on a grid). Cycles start at absolute deadlines
// (clock_nanosleep, TIMER_ABSTIME) start + n · period, so the rate does not
// drift. A run that follows a run which ended at its length (runFor) goes on
// on the same grid, so a loop run in pieces keeps its rate and its measured
// periods; the first run starts the grid. A run after a stop (requestStop, the
// stop flag, a hardware stop) resumes it at its first deadline from then, the
// deadlines of the stop skipped, so t and the control time stay the time since
// the first deadline. A cycle whose work ends after the next cycle's deadline is an
// overrun; the loop then skips the deadlines it missed (the next cycle starts
// at the first deadline still ahead, on the original grid) rather than running
// a burst of late cycles back to back. (schedule_resets stays 0 here: every
// overrun skips.)
//
// The thread's scheduling (SCHED_FIFO, CPU affinity, mlockall) is the
// caller's business: set it on the thread before calling run().
//
// With Options::step_simulation, a SimulatedRobotHW (the mock backend on
// `--clock wall`) stands in for hardware: it is stepped once per cycle, after
// write(), so its time step must be the cycle period (ConfigError otherwise).
#include <atomic>
#include <cstdint>

#include "servoloop/controller_manager/control_loop.hpp"
#include "servoloop/hardware_interface/simulated_robot_hw.hpp"

namespace servoloop::controller_manager {

struct WallClockLoopOptions : LoopCommonOptions {
  // The cycle period. 0 (default): 1 / the manager's update rate.
  Duration period{0.0};
  // Step the hardware once per cycle when it is a SimulatedRobotHW (see above).
  bool step_simulation = false;
};

class WallClockLoop final : public ControlLoop {
 public:
  using Options = WallClockLoopOptions;

  // Non-real-time. hw and manager must outlive the loop; the manager must be
  // built on hw. Throws servoloop::ConfigError when neither a period nor a
  // manager update rate is given, the period is not positive and finite, it
  // disagrees with the manager's update rate, or (step_simulation) hw is
  // simulated with a time step other than the period.
  WallClockLoop(hardware_interface::RobotHW& hw, ControllerManager& manager, Options options = {});

  // Runs until stop_requested, requestStop(), or a hardware stop.
  void run(const std::atomic<bool>& stop_requested) override;
  // Runs the cycles that start within `wall_time` from now, or, on a
  // continued grid, from its next deadline (also when the pause since the
  // last run missed it: the deadlines missed are skipped and count towards
  // the length; a run missed whole still runs one cycle); fewer if stopped.
  // A run after a stop resumes the grid at its first deadline from now, the
  // deadlines in between skipped (and counted towards the length, as a
  // pause's are).
  void runFor(Duration wall_time) override;

 private:
  void runCycles(std::int64_t run_length_ns, const std::atomic<bool>* external_stop);

  std::int64_t period_ns_ = 0;
  std::int64_t origin_ns_ = -1;  // the first deadline of the loop's first run: time 0 (-1 before)
  hardware_interface::SimulatedRobotHW* simulated_ = nullptr;  // stepped each cycle (step_simulation)

  // Real-time thread only.
  // How the last run left the deadline grid (-1: not known).
  struct Grid {
    bool continues = false;  // it ran its length: the next run carries on from it (no stop between)
    std::int64_t previous_start_ns = -1;
    std::int64_t previous_deadline_ns = -1;
    std::int64_t last_end_ns = -1;  // when wall_time_ns_ was last brought up to date
  };
  Grid grid_;
  std::uint64_t cycles_ = 0;
  // The grid the cycles covered since the origin: one period per cycle and
  // per deadline skipped (missed by an overrun or a pause, or stood still for
  // in a stop).
  std::int64_t control_time_ns_ = 0;
  std::int64_t wall_time_ns_ = 0;
};

}  // namespace servoloop::controller_manager
