#pragma once
// The control loop of a simulation, in lockstep with the physics as
// gazebo_ros_control runs it. One cycle is one physics step:
//
//   t = hw.simTime()       -- read at the start of a run, then counted in steps
//   hw.read(t, dt)
//   if a control update is due: manager.update(t, control period), cycle hook
//   hw.write(t, dt)        -- commands reach the simulator every physics step
//   hw.step()              -- simulated time advances by dt
//
// dt is the hardware's physics step (SimulatedRobotHW::timeStep()). The
// control period is an integer multiple k of dt: the manager is updated on the
// first cycle and then every k-th, with the control time that passed since its
// previous update (k·dt; the first update gets the nominal k·dt too).
//
// Pacing. Free-running (real_time_factor 0) runs cycles back to back. Paced,
// the cycle that simulates [t, t + dt] does not end before the wall time
// start + (t + dt − t_start) / real_time_factor: deadlines are absolute from
// the start of the run (integer nanoseconds, no drift). A loop that falls
// behind runs the following cycles without sleeping to catch up, but only
// while it is at most max_catch_up_steps physics steps of wall time late;
// beyond that it drops the backlog and restarts its schedule from now
// (counted as a schedule reset), so a stall (debugger, swapped-out process)
// is never followed by a long burst at full speed. Every cycle that ends after
// its deadline counts as an overrun.
//
// Statistics. Paced, every cycle is timed. Free-running, one cycle in
// kFreeRunningTimingStride is (the loop's first free-running cycle and every
// stride-th after it, counted across runs): the compute figures come from
// those, every cycle is counted, and the elapsed times are published with
// the timed cycles and at the end of each run.
#include <atomic>
#include <cstdint>

#include "servoloop/controller_manager/control_loop.hpp"
#include "servoloop/hardware_interface/simulated_robot_hw.hpp"
#include "servoloop/core/step_grid.hpp"

namespace servoloop::controller_manager {

struct SimulationLoopOptions : LoopCommonOptions {
  // Time between two manager updates, an integer multiple of the physics
  // step. 0 (default): the manager's update period (1 / update rate) when it
  // has one, else the physics step.
  Duration control_period{0.0};
  // Simulated seconds per wall second; 0 (default): free-running.
  double real_time_factor = 0.0;
  // How late (in physics steps of wall time) a paced loop may fall before it
  // stops catching up and restarts its schedule.
  std::uint32_t max_catch_up_steps = 10;
};

class SimulationLoop final : public ControlLoop {
 public:
  using Options = SimulationLoopOptions;

  // A free-running loop times every kFreeRunningTimingStride-th cycle.
  static constexpr std::uint64_t kFreeRunningTimingStride = 16;

  // Non-real-time. hw and manager must outlive the loop; the manager must be
  // built on hw. Throws servoloop::ConfigError when the physics step is not a
  // positive finite time, the control period is not an integer multiple of
  // it, the control period disagrees with the manager's update rate, or the
  // real-time factor is negative or not finite.
  SimulationLoop(hardware_interface::SimulatedRobotHW& hw, ControllerManager& manager, Options options = {});

  // Runs until stop_requested, requestStop(), or a hardware stop.
  void run(const std::atomic<bool>& stop_requested) override;
  // Runs ceil(sim_time / dt) physics steps (a tolerance of 1e-9 steps absorbs
  // rounding, so 1.0 s at dt = 0.001 s is exactly 1000 steps), or fewer if
  // stopped. Paced when real_time_factor > 0.
  void runFor(Duration sim_time) override;

  // Real-time. Exactly one cycle (one physics step), never paced, ignoring
  // stop requests. Returns error if any hardware call of the cycle failed,
  // deactivate if one asked to stop, else ok.
  ReturnType cycleOnce() noexcept;

  // Cycles run by a loop outside, which steps several robots' hardware in
  // one world (world/world_loop.hpp) and paces them itself. A run of them
  // starts with beginExternalRun() and ends with endExternalRun() (both on
  // the thread that runs the cycles, outside any cycle); externalCycle() is
  // one cycle, real-time, timed one in kFreeRunningTimingStride as
  // free-running cycles are, the wall time counted from beginExternalRun().
  void beginExternalRun() noexcept;
  ReturnType externalCycle() noexcept;
  void endExternalRun() noexcept;

  // Non-real-time, outside any run or cycle, after the hardware's reset():
  // the loop starts over as a new one would: its step count back to 0 and
  // its next cycle updating the controllers. Statistics are kept.
  void rewind() noexcept;

  Duration physicsStep() const noexcept { return physics_step_; }
  // k: the manager is updated every k-th physics step.
  std::uint64_t stepsPerControlUpdate() const noexcept { return steps_per_update_; }
  // Physics steps this loop has taken since it was built (or rewound).
  std::uint64_t stepsTaken() const noexcept { return steps_taken_.load(std::memory_order_acquire); }

 private:
  // One cycle's work; returns its combined hardware result.
  ReturnType runCycle(bool* control_updated) noexcept;
  // Reads the hardware's simulated time and finds its step on the grid.
  void syncHardwareStep() noexcept;
  void runCycles(std::uint64_t max_cycles, const std::atomic<bool>* external_stop);
  void runFreeCycles(std::uint64_t max_cycles, const std::atomic<bool>* external_stop);
  void runPacedCycles(std::uint64_t max_cycles, const std::atomic<bool>* external_stop);
  void publishElapsed() noexcept;

  hardware_interface::SimulatedRobotHW& hw_;
  Duration physics_step_;
  StepGrid step_grid_;  // simulated time exactly on the decimal step grid
  std::uint64_t steps_per_update_ = 1;
  double real_time_factor_ = 0.0;
  std::uint32_t max_catch_up_steps_ = 10;

  // Real-time thread only (atomic so stepsTaken() may be read elsewhere).
  std::atomic<std::uint64_t> steps_taken_{0};
  std::uint64_t last_update_step_ = 0;
  bool updated_before_ = false;
  std::int64_t wall_time_ns_ = 0;  // accumulated over runs and single cycles
  std::uint64_t free_cycles_ = 0;  // free-running and external cycles so far, for the timing stride
  std::int64_t external_run_start_ns_ = 0;   // cycle clock at beginExternalRun()
  std::int64_t external_wall_before_ns_ = 0;  // wall_time_ns_ then
  // The hardware's simulated time as a number of steps on step_grid_, when
  // it lies on the grid (hardware_step_known_).
  std::uint64_t hardware_step_ = 0;
  bool hardware_step_known_ = false;
};

}  // namespace servoloop::controller_manager
