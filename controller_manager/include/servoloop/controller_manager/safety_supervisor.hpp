#pragma once
// A robot's safety state, and what each state does to its commands.
//
//   running          normal operation.
//   protective_stop  the hardware failed: a read() or write() returned
//                    ReturnType::error (or threw), e.g. a drive that reports
//                    it is not ready, or a read() left a joint state NaN or
//                    infinite (the loop counts that as a read error). In that cycle the controllers that claim
//                    commands are stopped with safe outputs (zero effort and
//                    velocity, position held) and their fallback controllers
//                    started (ControllerManager::containHardwareFailure). The
//                    stop is latched: the robot stays in it, whatever the
//                    hardware does next, until `recover`.
//   emergency_stop   latched by `servoloop control estop on`, a true on the
//                    robot's `estop` topic, or the hardware's own input
//                    (RobotHW::emergencyStopInput). Controllers keep running
//                    and keep their state; before every write() their outputs
//                    are overridden: effort and velocity commands are 0,
//                    position commands hold the joint where it was when the
//                    stop engaged (its measured position; its command if the
//                    position is not finite). Released by `estop off` (or a false on the
//                    topic), refused while the hardware's input is still
//                    active; the robot then returns to the state under it.
//   fault            the loop stopped for the hardware (a call returned
//                    ReturnType::deactivate, or stop_after_failed_cycles was
//                    reached). Controllers are contained at once, as in a
//                    protective stop (after a read() that returned
//                    deactivate, before that cycle's update; fallbacks then
//                    command it), and no further cycle runs. `recover` runs
//                    the loop again.
//
// The state reported is the most severe that holds: fault, then emergency
// stop, then protective stop. Recovering (clearStop) leaves protective stop
// and fault; restarting the controllers that were stopped is the caller's
// business (the node's `control recover` does it).
//
// Threads. The pollHardwareInput/hardwareFailed/hardwareStopped/
// overrideCommands calls run on the loop's real-time thread: lock-free,
// allocation-free, never throwing. Everything else is safe from any thread.
#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "servoloop/controller_manager/loop_hardware_errors.hpp"
#include "servoloop/core/return_type.hpp"
#include "servoloop/core/time.hpp"
#include "servoloop/hardware_interface/robot_hw.hpp"

namespace servoloop::controller_manager {

enum class SafetyState : std::uint8_t { running, protective_stop, emergency_stop, fault };

// "running", "protective_stop", "emergency_stop", "fault".
const char* toString(SafetyState state) noexcept;

// Who engaged an emergency stop.
enum class EmergencyStopSource : std::uint8_t { command, topic, hardware };

// "command", "topic", "hardware input".
const char* toString(EmergencyStopSource source) noexcept;

class SafetySupervisor {
 public:
  // Non-real-time. Collects the command storage of hw's EffortJointInterface,
  // VelocityJointInterface and PositionJointInterface (hw must be
  // initialised, and must outlive this object).
  explicit SafetySupervisor(hardware_interface::RobotHW& hw);
  SafetySupervisor(const SafetySupervisor&) = delete;
  SafetySupervisor& operator=(const SafetySupervisor&) = delete;

  // --- Any thread ---

  SafetyState state() const noexcept;
  // Whether a protective stop holds, also while an emergency stop (more
  // severe, so what state() reports) is engaged on top of it.
  bool protectiveStopped() const noexcept;
  // Whether a protective stop or a fault holds (one reading of both): no
  // controller may start.
  bool startsForbidden() const noexcept;
  bool emergencyStopLatched() const noexcept { return estop_.load(std::memory_order_acquire) != kReleased; }
  // Who engaged the latched emergency stop; false when it is released.
  bool emergencyStopSource(EmergencyStopSource* source) const noexcept;
  // The hardware's input as last polled.
  bool hardwareEmergencyInput() const noexcept { return hardware_input_.load(std::memory_order_acquire); }
  // Latches the emergency stop (a no-op when already latched).
  void engageEmergencyStop(EmergencyStopSource source) noexcept;
  // Releases it. Returns false, with why, while the hardware's input is active.
  bool releaseEmergencyStop(std::string* why);
  // Leaves protective stop and fault (the emergency stop stays as it is).
  void clearStop() noexcept;
  // Counts of transitions, for tests and the run summary.
  std::uint64_t protectiveStops() const noexcept { return protective_stops_.load(std::memory_order_relaxed); }
  std::uint64_t emergencyStops() const noexcept { return emergency_stops_.load(std::memory_order_relaxed); }

  // Non-real-time. Why the robot is not running, e.g. "protective stop: the
  // hardware's read() returned an error at t = 1.234 s; after fixing the
  // cause run `servoloop control recover`"; empty when running.
  std::string reason() const;
  // Non-real-time. What the emergency stop does and how to release it, e.g.
  // "emergency stop engaged by topic: effort and velocity commands are 0,
  // position commands hold; release with `servoloop control estop off`";
  // empty when neither the latch nor the hardware's input holds it. The
  // node logs it on every engagement; reason() gives it in emergency stop.
  std::string emergencyStopText() const;

  // Non-real-time, only while the loop stands (after a fault, nothing polls
  // the input): reads RobotHW::emergencyStopInput here, so that a release
  // sees the input as it is now rather than as the last cycle saw it.
  void refreshHardwareInput() noexcept;

  // --- Real-time (the loop thread) ---

  // Reads RobotHW::emergencyStopInput; a true input latches the stop.
  void pollHardwareInput() noexcept;
  // A hardware call returned result. True when this moved the robot into
  // protective stop (the caller then contains the controllers); false for ok,
  // deactivate (see hardwareStopped) and when already stopped.
  bool hardwareFailed(HardwareCall call, ReturnType result, Time time) noexcept;
  // The loop stopped for the hardware: the robot is in fault. True on the
  // transition (the caller then contains the controllers).
  bool hardwareStopped(Time time) noexcept;
  // Right before every write(): in emergency stop, zero every effort and
  // velocity command and hold every position command.
  void overrideCommands() noexcept;

 private:
  void latchHeldPositions() noexcept;

  hardware_interface::RobotHW& hw_;
  std::vector<double*> zeroed_commands_;    // effort and velocity
  std::vector<double*> position_commands_;  // held
  std::vector<const double*> measured_positions_;  // the joints' positions, per position command
  std::vector<double> held_positions_;      // real-time thread: values at the stop
  bool holding_ = false;                    // real-time thread: held_positions_ are latched

  // The emergency stop's latch and who engaged it, in one word so that a
  // reader never sees the latch with an earlier stop's source: kReleased, or
  // 1 + the EmergencyStopSource.
  static constexpr std::uint8_t kReleased = 0;
  std::atomic<std::uint8_t> estop_{kReleased};
  std::atomic<bool> hardware_input_{false};
  std::atomic<bool> protective_{false};
  std::atomic<bool> fault_{false};
  // What caused the protective stop or fault; written by the real-time
  // thread before it sets protective_/fault_ (release), read after (acquire).
  std::atomic<HardwareCall> failed_call_{HardwareCall::read};
  std::atomic<ReturnType> failed_result_{ReturnType::error};
  std::atomic<double> failed_time_s_{0.0};
  std::atomic<std::uint64_t> protective_stops_{0};
  std::atomic<std::uint64_t> emergency_stops_{0};
};

}  // namespace servoloop::controller_manager
