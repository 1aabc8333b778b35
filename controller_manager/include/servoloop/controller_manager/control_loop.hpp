#pragma once
// The real-time control loop: what calls RobotHW::read, ControllerManager::update
// and RobotHW::write, cycle after cycle. Two kinds share this base:
//   - SimulationLoop (simulation_loop.hpp): lockstep with a SimulatedRobotHW's
//     physics steps, in simulated time, free-running or paced to a real-time factor;
//   - WallClockLoop (wall_clock_loop.hpp): real hardware, monotonic wall time,
//     absolute deadlines at the manager's update rate.
//
// Threads. run()/runFor()/cycleOnce() run the loop on the calling thread, which
// becomes the real-time thread; they allocate nothing once running, never log
// and never throw from inside a cycle. requestStop(), statistics(),
// takeHardwareErrorReport() and hardwareAskedToStop() are safe from any other
// thread while the loop runs.
//
// Hardware failures. A read/write/step that returns ReturnType::error is
// counted (LoopStatistics::hardware_errors) and reported once per episode
// (loop_hardware_errors.hpp); the loop goes on, as gazebo_ros_control and
// ros_control's hardware loops do, because a transient bus error should not
// drop the robot. Options::stop_after_failed_cycles makes a persistent failure
// stop the loop instead. A call that returns ReturnType::deactivate stops the
// loop at the end of that cycle (the hardware asked to be stopped cleanly). A
// hardware call that throws (it must not) counts as an error. So does a
// read() that leaves a joint state (position, velocity or effort of a joint
// in the RobotHW's JointStateInterface) NaN or infinite, whatever it returned:
// its report names the joint and the value, and with a safety supervisor it
// is a protective stop like any other read error, so no controller acts on
// it. The handles are collected when the loop is built (the hardware must be
// initialised by then), and checked after every read() without allocating.
#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "servoloop/controller_manager/loop_hardware_errors.hpp"
#include "servoloop/controller_manager/loop_statistics.hpp"
#include "servoloop/core/return_type.hpp"
#include "servoloop/hardware_interface/robot_hw.hpp"
#include "servoloop/core/time.hpp"

namespace servoloop::realtime {
class TopicBus;  // servoloop/realtime/topic_bus.hpp
}

namespace servoloop::controller_manager {

class ControllerManager;  // controller_manager.hpp
class SafetySupervisor;   // safety_supervisor.hpp

// What a node plugs into the loop to do its own real-time work each control
// cycle (e.g. publish the loop's clock, poll an emergency-stop input).
class LoopCycleHook {
 public:
  virtual ~LoopCycleHook() = default;
  // Real-time. Called right after every ControllerManager::update (in a
  // simulation, not on the physics steps between control updates), before the
  // commands are written. Must not allocate, lock, log or throw.
  virtual void afterUpdate(const Time& time, const Duration& period) noexcept = 0;
};

// What every loop kind is configured with, besides its timing.
struct LoopCommonOptions {
  // Called on the real-time thread after each update; may be null. Must outlive the loop.
  LoopCycleHook* cycle_hook = nullptr;
  // When set, its clock is set to the control time at the start of every
  // cycle, so messages published by controllers carry control (simulated) time.
  // May be null. Must outlive the loop.
  realtime::TopicBus* topic_bus = nullptr;
  // Stop the loop after this many cycles in a row with a hardware error;
  // 0 (default): never stop for errors, only count and report them.
  std::uint64_t stop_after_failed_cycles = 0;
  // The robot's safety states (safety_supervisor.hpp); may be null (no
  // safety layer: errors are only counted and reported). When set, a
  // hardware error puts the robot in protective stop and has the manager
  // stop its commanding controllers in that cycle, the hardware's
  // emergency-stop input is polled after every read(), an emergency stop
  // overrides the commands before every write(), and a hardware stop of the
  // loop is a fault. Must outlive the loop.
  SafetySupervisor* safety = nullptr;
};

class ControlLoop {
 public:
  // Loops that time every cycle time the controllers' updates in one of these.
  static constexpr std::uint32_t kUpdateTimingStride = 16;

  virtual ~ControlLoop() = default;
  ControlLoop(const ControlLoop&) = delete;
  ControlLoop& operator=(const ControlLoop&) = delete;

  // Runs cycles on the calling thread until stop_requested becomes true,
  // requestStop() is called, or the hardware asks to stop (see above).
  virtual void run(const std::atomic<bool>& stop_requested) = 0;

  // Runs for `duration` of control time (simulated time in a simulation, wall
  // time on real hardware), or until requestStop(). Throws servoloop::Error
  // for a negative or non-finite duration (before running anything).
  virtual void runFor(Duration duration) = 0;

  // Any thread. Ends the run in progress after its current cycle; if no run is
  // in progress, the next run returns before its first cycle. Each request
  // ends one run.
  void requestStop() noexcept { stop_requested_.store(true, std::memory_order_release); }

  // Any thread.
  const LoopStatistics& statistics() const noexcept { return statistics_; }
  // Any thread. Zeroes the statistics, the manager's controller timings
  // included, at the start of the next cycle (control time and wall time
  // run on).
  void requestStatisticsReset() noexcept;
  // Any thread. True once a hardware call returned ReturnType::deactivate or
  // stop_after_failed_cycles was reached; the loop then refuses to run on.
  bool hardwareAskedToStop() const noexcept { return hardware_stop_.load(std::memory_order_acquire); }
  // Non-real-time, while no run is in progress: lets the loop run again after
  // the hardware stopped it (e.g. once the hardware was re-initialised).
  void clearHardwareStop() noexcept { hardware_stop_.store(false, std::memory_order_release); }

  // Non-real-time, one thread at a time. The waiting hardware error report, once.
  std::optional<HardwareErrorReport> takeHardwareErrorReport() noexcept { return hardware_errors_.takeReport(); }
  // Non-real-time. Logs the waiting hardware error report, if any, with
  // servoloop::logger().error; true if there was one. A node's service thread
  // calls this now and then, alongside ControllerManager::processFaults().
  bool logHardwareErrorReport();

  // The time between two ControllerManager::update calls.
  Duration controlPeriod() const noexcept { return control_period_; }

  // Any thread. The hardware call (read(), write(), a simulation's step())
  // the loop's thread is in now. A call that does not return shows as the
  // same call, with the same number, on every look: a watch on another
  // thread tells how long it has been in it (RobotInstance::watchHardware).
  // Costs the cycle two relaxed atomic stores per call, no clock read.
  struct HardwareCallInProgress {
    bool in_call = false;
    HardwareCall call = HardwareCall::read;
    std::uint64_t number = 0;  // calls started so far, this one included
  };
  HardwareCallInProgress hardwareCallInProgress() const noexcept {
    const std::uint64_t ended = calls_ended_.load(std::memory_order_acquire);
    const std::uint64_t started = calls_started_.load(std::memory_order_acquire);
    return {started != ended, static_cast<HardwareCall>(current_call_.load(std::memory_order_relaxed)), started};
  }

 protected:
  ControlLoop(hardware_interface::RobotHW& robot_hw, ControllerManager& manager,
              const LoopCommonOptions& options, Duration control_period);

  // --- Real-time helpers for the cycle implementations ---

  // Calls read()/write() (exceptions count as errors) and records the result.
  ReturnType readHardware(Time time, Duration period, std::uint64_t cycle) noexcept;
  // Around every hardware call (read, write, step): hardwareCallInProgress().
  void beginHardwareCall(HardwareCall call) noexcept {
    current_call_.store(static_cast<std::uint8_t>(call), std::memory_order_relaxed);
    calls_started_.store(calls_started_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
  }
  void endHardwareCall() noexcept {
    calls_ended_.store(calls_ended_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
  }
  ReturnType writeHardware(Time time, Duration period, std::uint64_t cycle) noexcept;
  // Records the result of a hardware call (read() and write() here, step()
  // in the subclass). ok needs no bookkeeping; the rest goes to recordFailure().
  void recordHardwareResult(HardwareCall call, ReturnType result, Time time, std::uint64_t cycle) noexcept {
    if (result != ReturnType::ok) recordFailure(call, result, time, cycle);
  }
  // Sets the topic bus clock (if any) to time.
  void setBusTime(Time time) noexcept;
  // ControllerManager::update, then the cycle hook.
  void updateControllers(Time time, Duration period) noexcept;
  // Closes the cycle (control time `time`): error episode bookkeeping; sets
  // hardwareAskedToStop() when the hardware said deactivate or failed too
  // often in a row (with a safety supervisor: a fault).
  void finishCycle(Time time) noexcept;
  // True when the run should end before the next cycle.
  bool shouldStop(const std::atomic<bool>* external_stop) const noexcept;
  // Clears a consumed stop request at the end of a run.
  void consumeStopRequest() noexcept { stop_requested_.store(false, std::memory_order_release); }

  // Whether this cycle's phases (read, each controller's update, write) are
  // timed: every cycle unless a loop times only some (a free-running
  // simulation, see LoopStatistics).
  void setPhaseTiming(bool timed) noexcept;
  // A loop that times its phases in every cycle (the wall clock, a paced
  // simulation) calls this at the start of each cycle, after
  // applyRequestedStatisticsReset(): the controllers' updates are then timed
  // in one cycle of kUpdateTimingStride only (the first after the loop's
  // start or a statistics reset, and every stride-th after it). A timed
  // update costs a clock read per controller, more than a small controller's
  // update itself; one cycle in 16 gives the same percentiles for controllers
  // whose cost does not jump from cycle to cycle.
  void sampleUpdateTiming() noexcept;
  // At the start of a cycle: a statistics reset another thread asked for.
  void applyRequestedStatisticsReset() noexcept;

  hardware_interface::RobotHW& robotHW() noexcept { return robot_hw_; }
  LoopStatistics& mutableStatistics() noexcept { return statistics_; }

 private:
  // non_finite: set when an ok read() left a joint state not finite.
  void recordFailure(HardwareCall call, ReturnType result, Time time, std::uint64_t cycle,
                     const NonFiniteJointState* non_finite = nullptr) noexcept;
  // Real-time. True when every joint state is finite; otherwise false, with
  // the first joint state that is not in *found.
  bool jointStatesFinite(NonFiniteJointState* found) const noexcept;

  hardware_interface::RobotHW& robot_hw_;
  ControllerManager& manager_;
  LoopCommonOptions options_;
  Duration control_period_;

  // Every joint state the hardware offers, three per joint (position,
  // velocity, effort), and the joints' names; collected at construction.
  std::vector<const double*> joint_state_values_;
  std::vector<std::string> joint_state_names_;

  LoopStatistics statistics_;
  LoopHardwareErrors hardware_errors_;
  std::atomic<bool> stop_requested_{false};
  std::atomic<bool> hardware_stop_{false};
  // Written by the loop's thread only (hardwareCallInProgress).
  std::atomic<std::uint64_t> calls_started_{0};
  std::atomic<std::uint64_t> calls_ended_{0};
  std::atomic<std::uint8_t> current_call_{0};
  bool deactivate_this_cycle_ = false;  // real-time thread only
  bool time_phases_ = true;             // real-time thread only
  std::uint32_t update_timing_countdown_ = 0;  // cycles until the next timed update; real-time thread only
};

}  // namespace servoloop::controller_manager
