#pragma once
// One robot of a running node: its hardware (a simulation backend plugin, or
// a hardware plugin named by the launch file's `hardware:`), its topic bus,
// its controller manager and the loop that runs it:
//   - simulated in lockstep (the default): a SimulationLoop whose cycles the
//     node's world loop runs, together with every other simulated robot's,
//     stepping their shared physics once per cycle (world/world_loop.hpp);
//     the robot is a member of that world (WorldMember);
//   - on the wall clock (hardware, or a simulated robot with world.clock:
//     wall): a WallClockLoop on a real-time thread of the robot's own.
//
// On the wall clock, time is wall time since the loop's start (its first
// deadline); timed publications and --duration count the deadlines the loop
// covered (one period each, a cycle's or one an overrun skipped), and
// controllers get the measured period. What follows about simulated time
// holds for the SimulationLoop.
//
// Between two runs of cycles, with no cycle of the robot in progress, the
// thread that drives it (the world's or its own) does the non-real-time work
// that must land on an exact simulated time:
//   - timed publications: a publication at time T is published after the last
//     physics step before T, so the first control update at a simulated time
//     >= T sees it (exact to the control cycle; the loop pauses for the
//     microseconds a publish takes, between cycles, never inside one);
//   - before the first physics step, the launch file's controllers are
//     started (see startLaunchControllers), so that their starting(), which
//     resets a controller's command to the measured state as in ros_control,
//     comes before the publications at t = 0: those are seen by the first
//     control update, at t = 0, and stamped 0;
//   - when free-running (real-time factor 0), the bus is flushed every 10 ms
//     of simulated time, so subscribers (recorders, `topic echo`) get every
//     message even when the loop runs a thousand times faster than the bus's
//     delivery thread wakes up.
//
// Each robot has its own TopicBus, stamped with its own simulated time,
// counted from when it was spawned (a robot spawned later has a later zero).
// Everything here is non-real-time except what runs in the loop's cycles.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <urdf_model/model.h>

#include "servoloop/controller_manager/controller_manager.hpp"
#include "servoloop/node/contact_states_publisher.hpp"
#include "servoloop/node/ground_truth_publisher.hpp"
#include "servoloop/node/launch_file.hpp"
#include "servoloop/node/plugin_controller_factory.hpp"
#include "servoloop/params/parameter_store.hpp"
#include "servoloop/plugin/plugin_loader.hpp"
#include "servoloop/controller_manager/control_loop.hpp"
#include "servoloop/controller_manager/safety_supervisor.hpp"
#include "servoloop/controller_manager/simulation_loop.hpp"
#include "servoloop/realtime/action_registry.hpp"
#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/hardware_interface/robot_hw.hpp"
#include "servoloop/hardware_interface/simulated_robot_hw.hpp"
#include "servoloop/hardware_interface/simulated_world.hpp"
#include "servoloop/world/world_loop.hpp"

namespace servoloop::node {

// What a robot needs from the world it is spawned into.
struct RobotWorld {
  std::shared_ptr<plugin::PluginLoader> plugins;  // backends and controllers
  params::ParameterStore* parameters = nullptr;   // the node's store (params files already loaded)
  WorldSettings world;                    // backend, physics step, gravity, ground plane
  double update_rate_hz = 0.0;            // controller manager rate; 0: 1 / time step
  double real_time_factor = 0.0;          // 0: free-running
  RealtimeSettings realtime;              // the launch file's; a robot's own win
  // The node's simulated world and its loop: a simulated robot in lockstep
  // is built into the world and runs on the loop (both required for it);
  // robots on the wall clock do not use them.
  hardware_interface::SimulatedWorld* simulated_world = nullptr;
  world::WorldLoop* world_loop = nullptr;
};

struct JointReading {
  std::string name;
  double position = 0.0;  // rad or m
  double velocity = 0.0;  // rad/s or m/s
  double effort = 0.0;    // N·m or N
};

class RobotInstance final : public world::WorldMember {
 public:
  // Reads the URDF, resolves the namespace (robot_namespace.hpp), writes the
  // world settings to <ns>/sim/{time_step,gravity,ground_plane}, creates and
  // initialises the backend, the bus (delivery started), the manager and the
  // loop, and loads spec's controllers and stopped_controllers (a controller
  // that fails to load is logged and left out; the robot carries on). The
  // loop thread starts the controllers before its first physics step. Throws
  // ConfigError naming the URDF, backend or setting at fault.
  RobotInstance(const RobotSpec& spec, const RobotWorld& world);
  // stop(), then stops and unloads every controller.
  ~RobotInstance();
  RobotInstance(const RobotInstance&) = delete;
  RobotInstance& operator=(const RobotInstance&) = delete;

  // Before start(): a message to publish at a simulated time.
  void addTimedPublication(const TimedPublication& publication);

  // Starts the robot's loop: its thread, or it joins the world loop (once
  // the world runs, start() returns after the robot's launch controllers
  // started; before that, they start when the world does); with a duration it ends after
  // that much simulated time, else when stopped (or when the hardware asks
  // to stop).
  void start(std::optional<double> duration_s);
  // Any thread. Ends the loop after its current cycle (joins the robot's
  // thread, or leaves the world loop).
  void stop();
  // True once the loop has ended (or was never started).
  bool finished() const { return !started() || loop_done_.load(); }
  // Non-real-time, before start(): called on the loop thread right after its
  // loop has ended (finished() is then true), e.g. to wake whoever waits for it.
  void setFinishedCallback(std::function<void()> callback) { on_finished_ = std::move(callback); }

  // Non-real-time, with the loop stopped: stops every running controller (their
  // stopping() runs) and unloads every controller. Idempotent.
  void shutdownControllers();

  const std::string& robotNamespace() const { return namespace_; }
  const std::string& robotName() const { return robot_name_; }
  const std::filesystem::path& urdfPath() const { return urdf_path_; }
  // The robot's URDF as ROS's robot_description holds it: xacro expanded,
  // nothing else changed.
  const std::string& robotDescription() const { return robot_description_; }
  controller_manager::ControllerManager& manager() { return *manager_; }
  realtime::TopicBus& topics() { return *bus_; }
  realtime::ActionRegistry& actions() { return *actions_; }
  hardware_interface::RobotHW& hardware() { return *hw_; }
  controller_manager::ControlLoop& loop() { return *loop_; }
  // True when the robot runs on the wall clock (hardware, or world.clock: wall).
  bool wallClock() const { return sim_loop_ == nullptr; }
  const std::shared_ptr<const urdf::ModelInterface>& model() const { return model_; }
  const std::string& backendName() const { return backend_name_; }

  // Any thread: control time the loop has advanced, s (simulated time, or
  // on the wall clock the deadlines covered × the period).
  double simTime() const;
  // Joint state from the joint state interface. Exact once the loop has
  // stopped; while it runs, values may be one cycle apart.
  std::vector<JointReading> joints() const;
  // Joints with the interfaces offering them (JointStateInterface,
  // EffortJointInterface, ...).
  std::vector<std::pair<std::string, std::vector<std::string>>> jointInterfaces() const;

  // The robot's safety states (controller_manager/safety_supervisor.hpp).
  // Its `estop` topic (std_msgs/Bool) engages (true) and releases (false)
  // the emergency stop.
  controller_manager::SafetySupervisor& safety() { return *safety_; }
  // Non-real-time. Engages or releases the emergency stop; a release fails
  // while the hardware's own input is active.
  controller_manager::ServiceResult setEmergencyStop(bool engaged, controller_manager::EmergencyStopSource source);
  // Non-real-time. Loads a controller (ControllerManager::loadController),
  // except one whose `joint` or `joints` parameter names a joint left out of
  // the simulation (its link has no mass): that fails with why, instead of
  // with a missing interface or handle.
  controller_manager::ServiceResult loadController(const std::string& name);
  // Non-real-time; blocks until done. Leaves protective stop or fault: the
  // loop runs again (after a fault), the controllers the stop had stopped
  // are started again (stopping the fallbacks that took their resources),
  // and the robot must then stay running for a few cycles. Fails, saying
  // why, while the emergency stop is engaged, when a controller does not
  // start, or when the hardware fails again at once.
  controller_manager::ServiceResult recover();
  // Non-real-time, one thread (the node's main loop, every tick). Watches the
  // loop's hardware calls (ControlLoop::hardwareCallInProgress): a read(),
  // write() or step() that has not returned for max(1 s, 20 control
  // periods) makes the robot stuck — logged once, as an error naming the
  // call and how long; `control safety` reports a fault with that reason;
  // what needs a cycle of the robot (switch, load, unload, recover) is
  // refused at once; and stop() does not wait for it. It clears (logged)
  // when the call returns.
  void watchHardware(std::chrono::steady_clock::time_point now);
  // Any thread. Why the robot is stuck; empty when it is not.
  std::string stuckReason() const;
  // Any thread. stop() left the robot's loop thread inside its hardware call
  // (it never returned): the robot must be left alive, unused, until the
  // process ends (Node::shutdown does so).
  bool abandoned() const { return abandoned_.load(); }

  // Non-real-time, one thread (the node's main loop). Logs an emergency stop
  // the hardware's input engaged since the last call (a command or the topic
  // log their own in setEmergencyStop).
  void logHardwareEmergencyStops();

  // Non-real-time (the node's service thread calls it now and then).
  // Publishes the robot's diagnostics (robot_diagnostics.hpp) on
  // <ns>/diagnostics when a second of wall time has passed since the last.
  void publishDiagnosticsIfDue();

  // Non-real-time, only while the world stands between two segments
  // (WorldLoop::whilePaused): the robot goes back to the start of its run,
  // as Gazebo's reset_simulation does, and as a fresh launch would start it:
  // its running controllers are stopped (stopping()), its simulated
  // hardware reset (joints at their initial positions and at rest, the base
  // at its spawn pose, commands zero, time 0), its loop rewound, then the
  // launch file's controllers and those that were running started again as
  // at launch (starting(), so their state resets; a launch controller that
  // had failed starts again too), and the launch file's timed publications are published again
  // at their times. The world's own reset (SimulatedWorld::restart) follows
  // the reset of its every robot. Returns why a controller did not start
  // again (empty when all did). A controller with a parameter under one of
  // `changed_parameters` (full names) is unloaded and loaded again while
  // stopped, so that it starts with the new values. Throws servoloop::Error
  // for a robot on hardware or on the wall clock (hardware cannot be reset).
  std::string resetToStart(const std::vector<std::string>& changed_parameters = {});
  // Throws what resetToStart would refuse for, changing nothing: a robot on
  // hardware or the wall clock, a controller switch waiting for a cycle.
  void checkResettable() const;

  // What the launch asked for and did not happen: controllers that did not
  // load, switches that did not start them. Read after stop().
  const std::vector<std::string>& launchFailures() const { return launch_failures_; }

 private:
  // --- as a member of the world (robot_loop_driver.cpp) ---
  void enterWorld() override;
  std::uint64_t betweenSegments() override;
  void leaveWorld() override;
  controller_manager::SimulationLoop& simulationLoop() override { return *sim_loop_; }
  // The run has ended: last delivery, finished() true, the node told.
  void finishRun();
  // After a fault, on the world's thread: whether recover() asked to run
  // again (then the stop is cleared and recover() told).
  bool resumeIfRecoveryRequested();

  bool started() const { return loop_thread_.joinable() || world_started_.load(); }
  void driveLoop(std::optional<double> duration_s);
  void driveWallClockLoop(std::optional<double> duration_s);
  std::uint64_t stepsAt(double time_s) const;
  void publishDue(std::uint64_t steps_taken);
  void publishDueAt(double time_s);
  void publish(const TimedPublication& publication);
  void createLoop(bool hardware_robot, bool wall_clock, double update_rate_hz);
  void loadControllers(const RobotSpec& spec, const params::ParameterStore& store);
  std::string whereParametersAre(const std::string& name, const params::ParameterStore& store) const;
  void startLaunchControllers();
  using StartFailure = std::function<void(const std::vector<std::string>& controllers, const std::string& why)>;
  void startControllersAtStart(const std::vector<std::string>& names, const StartFailure& failed);
  void reportLaunchStartFailure(const std::vector<std::string>& controllers, const std::string& why);
  bool waitForRecovery();
  // Why the safety state forbids this switch now (empty: it is allowed): no
  // start under a fault or a protective stop. The manager asks it
  // (ControllerManager::setSwitchGuard).
  std::string switchRefusal(const controller_manager::SwitchRequest& request) const;
  controller_manager::ServiceResult restartStoppedControllers(std::vector<std::string>* restarted);
  bool waitForCycles(std::uint64_t cycles, double timeout_s) const;

  std::string namespace_;
  std::string robot_name_;
  std::filesystem::path urdf_path_;
  std::string robot_description_;
  std::vector<std::string> left_out_joints_;  // simulatableUrdf left them out (massless links)
  params::ParameterStore* parameters_ = nullptr;
  std::string backend_name_;
  double real_time_factor_ = 0.0;
  RealtimeSettings realtime_;  // applied on the loop thread before its first cycle
  std::shared_ptr<const urdf::ModelInterface> model_;

  // Destruction order matters: loop, manager (controllers), bus, backend.
  plugin::PluginPtr<hardware_interface::RobotHW> backend_;
  hardware_interface::RobotHW* hw_ = nullptr;
  hardware_interface::SimulatedRobotHW* sim_hw_ = nullptr;  // null for hardware
  std::unique_ptr<realtime::TopicBus> bus_;
  std::unique_ptr<realtime::ActionRegistry> actions_;
  // Floating bases only; the loop calls it, so it outlives loop_.
  std::unique_ptr<GroundTruthPublisher> ground_truth_;
  std::unique_ptr<ContactStatesPublisher> contact_states_;  // the contact sensors' topics (world loop only)
  std::unique_ptr<controller_manager::SafetySupervisor> safety_;  // on hw_; the loop uses it
  realtime::Subscription estop_subscription_;                     // <ns>/estop
  std::unique_ptr<controller_manager::ControllerManager> manager_;
  std::unique_ptr<controller_manager::ControlLoop> loop_;
  controller_manager::SimulationLoop* sim_loop_ = nullptr;  // loop_, in lockstep; null on the wall clock

  // Loaded controllers of spec.controllers, started by the loop thread before
  // its first physics step.
  std::vector<std::string> launch_controllers_;
  std::vector<std::string> launch_failures_;  // written before the loop runs, read after it stopped
  std::vector<TimedPublication> publications_;  // sorted by time before start
  std::size_t next_publication_ = 0;            // loop thread only

  std::mutex lifecycle_mutex_;
  std::thread loop_thread_;
  // In the world: the loop that runs the robot's cycles, and the run's end
  // and flush interval in the robot's physics steps (the world's thread).
  world::WorldLoop* world_loop_ = nullptr;
  std::atomic<bool> world_started_{false};
  std::uint64_t world_end_steps_ = 0;
  std::uint64_t world_flush_steps_ = 0;
  bool world_duration_ = false;  // the run has a duration
  std::atomic<bool> stop_requested_{false};
  std::atomic<bool> loop_done_{false};
  // A loop stopped by the hardware (fault) waits for recover() or stop().
  std::mutex recovery_mutex_;
  std::condition_variable recovery_wake_;
  bool recovery_requested_ = false;
  bool resumed_ = false;  // set by the loop thread when it runs again after a fault
  bool waiting_for_recovery_ = false;  // the loop thread stands in waitForRecovery
  // publishDiagnosticsIfDue's thread only.
  std::chrono::steady_clock::time_point next_diagnostics_{};
  std::uint64_t diagnostics_overruns_ = 0;
  std::uint64_t emergency_stops_seen_ = 0;  // logHardwareEmergencyStops
  std::function<void()> on_finished_;
  bool controllers_shut_down_ = false;
  // watchHardware's: the call it saw last, and since when (its thread only).
  std::uint64_t watched_call_ = 0;
  std::chrono::steady_clock::time_point watched_since_{};
  std::atomic<bool> stuck_{false};
  mutable std::mutex stuck_mutex_;
  std::string stuck_call_;  // the call watched ("read", "write", "step"); under stuck_mutex_
  std::atomic<bool> abandoned_{false};
};

}  // namespace servoloop::node
