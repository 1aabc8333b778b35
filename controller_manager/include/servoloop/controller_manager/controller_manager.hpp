#pragma once
// The controller manager: loads controllers, switches them on the real-time
// thread, runs each running controller at its own rate, and contains their
// faults. ros_control's controller_manager::ControllerManager, without ROS.
//
// Threads. update() is the real-time side: it never allocates, locks a mutex,
// logs or throws. Every other member function is non-real-time and may be
// called from any thread (they serialise on an internal mutex the real-time
// side never touches). The running-controller list is double-buffered:
// load/unload publish a new list and wait (briefly) until the real-time thread
// no longer reads the old one; a switch is handed over as a pending request
// that the real-time thread carries out at the start of its next update().
//
// Errors. Every service returns a ServiceResult: ok, or false with a message
// naming the controller, the parameter and the fix. The same message is logged
// with servoloop::logger().error. Services do not throw for bad requests.
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "servoloop/controller_manager/controller_base.hpp"
#include "servoloop/controller_manager/controller_context.hpp"
#include "servoloop/controller_manager/controller_factory.hpp"
#include "servoloop/controller_manager/controller_spec.hpp"
#include "servoloop/controller_manager/duration_statistics.hpp"
#include "servoloop/controller_manager/switch_request.hpp"
#include "servoloop/controllers/pid.hpp"
#include "servoloop/hardware_interface/robot_hw.hpp"
#include "servoloop/core/time.hpp"

namespace servoloop::controller_manager {

namespace detail {
struct ControllerEntry;
struct FaultRecord;
}  // namespace detail

// The gains of one of a controller's tunable PIDs (ControllerBase::tunablePids).
struct PidGains {
  std::string pid;  // its name under the controller, e.g. "pid", "gains/joint1"
  controllers::Pid::Gains gains;
};

// Outcome of a manager service.
struct ServiceResult {
  bool ok = false;
  std::string message;  // why it failed; empty on success
  explicit operator bool() const { return ok; }
  static ServiceResult success() { return {true, {}}; }
  static ServiceResult failure(std::string why) { return {false, std::move(why)}; }
};

// How often a controller can run inside a manager of a given rate.
struct UpdateRateChoice {
  std::uint32_t divisor = 1;  // the controller updates every divisor-th manager cycle
  double rate_hz = 0.0;       // manager rate / divisor (0 if the manager has no fixed rate)
  bool exact = true;          // false when the requested rate was not achievable
};

// The manager-rate divisor nearest to a requested controller rate. A request
// <= 0 means "every cycle". A request above the manager rate, or one that does
// not divide it, gets the nearest achievable rate (exact = false).
UpdateRateChoice chooseUpdateRate(double manager_rate_hz, double requested_rate_hz);

class ControllerManager {
 public:
  // The controller's parameter subtree (<ns>/<name>) for a controller name; a
  // null or undefined node when there is none.
  using ParameterLookup = std::function<YAML::Node(const std::string& controller_name)>;
  // Why a switch may not be carried out now (empty: it may), e.g. a robot
  // whose safety state forbids starting controllers.
  using SwitchGuard = std::function<std::string(const SwitchRequest& request)>;

  // A lookup into a YAML map of controller names to their parameters (the
  // robot namespace's node of a ros_control controller YAML).
  static ParameterLookup lookupIn(YAML::Node namespace_parameters);

  // robot_hw: the hardware controllers are initialised on (must outlive the
  //   manager). factory: where controller types come from (kept alive as long
  //   as any controller it made). parameters: the controllers' parameters.
  // context_template: robot namespace, topic bus, parameter store and robot
  //   model handed to every controller (name/params are filled per controller).
  // update_rate_hz: the rate update() is called at; 0 when unknown (every
  //   controller then updates every cycle).
  // Throws servoloop::Error if robot_hw or factory is null.
  ControllerManager(hardware_interface::RobotHW* robot_hw, std::shared_ptr<ControllerFactory> factory,
                    ParameterLookup parameters, ControllerContext context_template = {},
                    double update_rate_hz = 0.0);
  // Destroys every controller. The real-time loop must have stopped calling
  // update() before.
  ~ControllerManager();
  ControllerManager(const ControllerManager&) = delete;
  ControllerManager& operator=(const ControllerManager&) = delete;

  // --- Services (non-real-time) ---

  // Creates the controller named `name` with the type from its `type`
  // parameter and initialises it. Fails if the name is loaded already, `type`
  // is missing or unknown, `update_rate` is not a number, or init returned
  // false or threw (the message carries what it threw).
  ServiceResult loadController(const std::string& name);

  // Destroys a loaded controller (on the calling thread). Fails if it is
  // unknown, running, or part of a switch still waiting for the real-time thread.
  ServiceResult unloadController(const std::string& name);

  // Validates the request (ros_control's rules, see switch_request.hpp), checks
  // resource conflicts and the hardware's prepareSwitch, then waits until the
  // real-time thread has carried it out, up to request.timeout_s (0: forever).
  // Fails if validation fails, it timed out (nothing was switched), or a
  // started controller failed in starting().
  ServiceResult switchController(const SwitchRequest& request);
  ServiceResult switchController(const std::vector<std::string>& start_controllers,
                                 const std::vector<std::string>& stop_controllers,
                                 SwitchStrictness strictness, bool start_asap = false,
                                 double timeout_s = 0.0);

  // Non-real-time. A check every later switch must pass. It is asked after
  // the switch has read what the real-time thread last contained (see
  // containHardwareFailure), so a stop the guard does not see yet makes the
  // real-time thread drop the switch instead of carrying it out.
  void setSwitchGuard(SwitchGuard guard);

  // Validates like switchController and hands the switch to the real-time
  // thread without waiting (timeout_s is ignored). For callers that run
  // update() themselves: request, then call update(), then check
  // switchPending(), then finishSwitch(). Fails if another switch is still pending.
  ServiceResult requestSwitch(const SwitchRequest& request);
  // Non-real-time. The outcome of the switch requestSwitch handed over, once
  // the real-time thread has carried it out (switchPending() false): what
  // switchController would have returned (a hardware that could not change
  // its modes, a controller whose starting() failed). Success when there is
  // no outcome waiting. A switch nobody finishes is finished, and a failure
  // logged, by the next switch request.
  ServiceResult finishSwitch();
  // True while a requested switch waits for (or is being carried out by) the
  // real-time thread.
  bool switchPending() const;

  // Every loaded controller, in load order.
  std::vector<ControllerSpec> listControllers();
  // Every type the factory can create.
  std::vector<std::string> listControllerTypes();

  // Asks the factory to reload its libraries. Refuses while controllers are
  // loaded, unless force_kill: then running controllers are stopped (one
  // STRICT switch, waiting up to stop_timeout_s) and all are unloaded first.
  ServiceResult reloadControllerLibraries(bool force_kill, double stop_timeout_s = 5.0);

  // Logs (servoloop::logger().error) and returns the faults the real-time
  // thread contained since the last call. Each fault is reported once. The
  // services call it too, so a control loop's service thread only needs to
  // call it now and then to get faults logged promptly.
  std::vector<ControllerFault> processFaults();

  // The loaded controller of that name, or nullptr. Valid until it is unloaded.
  ControllerBase* getController(const std::string& name);

  // The gains of each tunable PID of a loaded controller, in the controller's
  // order (none for a controller without PIDs). Fails when no controller of
  // that name is loaded.
  ServiceResult controllerGains(const std::string& name, std::vector<PidGains>& gains);
  // Changes one of them, as ros_control's dynamic_reconfigure of the PID does:
  // the controller takes the new gains at its next update, on the real-time
  // thread, without allocating or waiting (running or not). Fails, changing
  // nothing, for an unknown controller or PID (naming the PIDs it has), a
  // gain that is not finite, or i_min > 0 or i_max < 0 (control_toolbox's
  // ranges: i_clamp_min <= 0 <= i_clamp_max).
  ServiceResult setControllerGains(const std::string& name, const PidGains& gains);

  // Any thread. How long each loaded controller's update() took, in load
  // order, over the timed cycles since the last reset (see setUpdateTiming).
  std::vector<std::pair<std::string, DurationSnapshot>> updateTimes();
  // Any thread. Zeroes those at the start of the next update().
  void requestUpdateTimingReset() noexcept { update_timing_reset_.store(true, std::memory_order_release); }

  double updateRate() const noexcept { return update_rate_hz_; }
  hardware_interface::RobotHW* robotHW() const noexcept { return robot_hw_; }

  // --- Control cycle (real-time) ---

  // Carries out a pending switch (stopping(), RobotHW::doSwitch, starting()),
  // then updates every running controller that is due this cycle with the
  // control time since its previous update. Faults are contained: the
  // controller is stopped with safe outputs and marked failed; the others go
  // on. A controller that faults in update() (throws, returns an error or
  // writes a non-finite command) and names `fallback_controllers` has them
  // started in the same cycle. `period` is the manager's cycle period (each
  // controller gets its own).
  void update(const Time& time, const Duration& period) noexcept;

  // Real-time, on the thread that calls update() (between two updates). The
  // robot's hardware failed (a protective stop, safety_supervisor.hpp): every
  // running controller that claims a command is stopped with safe outputs and
  // marked failed with FaultKind::hardware_failed and `why` (copied,
  // truncated), and its fallback controllers are started, as for a fault in
  // update(). Controllers that claim no command (state broadcasters) run on.
  // Returns how many controllers were stopped.
  std::size_t containHardwareFailure(const Time& time, const char* why) noexcept;

  // Real-time. Whether the next update()s time each controller's update()
  // (updateTimes). Off by default: a bare manager (a hand-written main calling
  // update()) reads no clock. A control loop switches it on for the cycles it
  // samples: one in 16 (ControlLoop::kUpdateTimingStride, and
  // SimulationLoop::kFreeRunningTimingStride for a free-running simulation);
  // a timed cycle reads the cycle clock (loop_clock::cycleClockNs) once per
  // updated controller, plus once.
  void setUpdateTiming(bool timed) noexcept { time_updates_ = timed; }

 private:
  enum class SwitchPhase : std::uint8_t { idle, pending, executing, done };

  // What the real-time thread carries out for one switch; built beforehand so
  // carrying it out allocates nothing.
  struct SwitchPlan {
    std::vector<detail::ControllerEntry*> stop;
    std::vector<detail::ControllerEntry*> start;
    std::vector<hardware_interface::ControllerInfo> start_infos;
    std::vector<hardware_interface::ControllerInfo> stop_infos;
    // Set by the real-time thread: start[i] failed in starting().
    std::vector<std::uint8_t> start_failed;
    // fallback_starts_ when the plan was made: a fallback started since may
    // hold resources the plan gives away, so the plan is not carried out.
    std::uint64_t fallback_epoch = 0;
    bool aborted = false;  // set by the real-time thread
    bool hardware_refused = false;  // RobotHW::doSwitch failed (real-time thread): nothing switched
    std::array<char, 256> hardware_error{};  // why, truncated (real-time thread)
  };

  // Non-real-time helpers; the caller holds services_mutex_.
  detail::ControllerEntry* findEntry(const std::string& name) const;
  ServiceResult prepareSwitchLocked(const SwitchRequest& request, bool* nothing_to_do);
  ServiceResult waitForSwitchLocked(double timeout_s);
  // After the real-time thread set done; `announce`: log a switch that worked.
  ServiceResult completeSwitchLocked(bool announce);
  void finishDoneSwitchLocked();
  ServiceResult unloadLocked(const std::string& name);
  void publishRealtimeList(std::vector<detail::ControllerEntry*> list);
  void waitUntilRealtimeLeaves(int list_index) const;
  std::vector<ControllerFault> processFaultsLocked();
  ServiceResult fail(std::string message) const;

  // Real-time helpers.
  int enterRealtimeList() noexcept;
  void executeSwitch(const Time& time) noexcept;
  // One controller's update, when it runs and is due (inline in update()'s
  // loop). kTimed: clock_ns is the loop clock's last reading, which the
  // update's time is taken from and which moves on to the reading after it.
  template <bool kTimed>
  void updateController(detail::ControllerEntry& entry, const Time& time, std::int64_t& clock_ns) noexcept;
  // Out of line, the rare ends of an update that returned: an error or
  // deactivate result, a non-finite command. True when one was handled.
  bool handleUpdateResult(detail::ControllerEntry& entry, ReturnType result, const Time& time) noexcept;
  void contain(detail::ControllerEntry& entry, FaultKind kind, const char* what) noexcept;
  // contain(), then start the controller's fallback controllers (if any) in
  // the same cycle.
  void containInUpdate(detail::ControllerEntry& entry, FaultKind kind, const char* what, const Time& time,
                       std::size_t command_index = ControllerBase::kAllCommandsFinite, double value = 0.0) noexcept;
  // starting() of one controller outside a switch plan; false if it failed
  // (then contained).
  bool startNow(detail::ControllerEntry& entry, const Time& time) noexcept;

  hardware_interface::RobotHW* robot_hw_;
  std::shared_ptr<ControllerFactory> factory_;  // declared before entries_: outlives them
  ParameterLookup parameters_;
  SwitchGuard switch_guard_;  // under services_mutex_
  ControllerContext context_template_;
  double update_rate_hz_;

  mutable std::mutex services_mutex_;
  // Every loaded controller, in load order (non-real-time side).
  std::vector<std::unique_ptr<detail::ControllerEntry>> entries_;

  // Double-buffered list the real-time thread iterates.
  std::vector<detail::ControllerEntry*> realtime_lists_[2];
  std::atomic<int> realtime_current_list_{0};
  std::atomic<int> realtime_reading_list_{-1};  // -1 while outside update()
  // The real-time side of that handshake needs only a compiler barrier when
  // the publisher can fence every thread (src/asymmetric_fence.hpp).
  bool asymmetric_list_fence_ = false;

  std::atomic<SwitchPhase> switch_phase_{SwitchPhase::idle};
  SwitchPlan switch_plan_;

  std::uint64_t cycle_ = 0;  // real-time thread only
  bool time_updates_ = false;  // real-time thread only
  std::atomic<bool> update_timing_reset_{false};
  // Fallback starts so far (real-time thread writes; switches compare).
  std::atomic<std::uint64_t> fallback_starts_{0};
};

}  // namespace servoloop::controller_manager
