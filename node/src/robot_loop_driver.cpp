// How a robot's loop is driven: by a thread of its own (a robot on the wall
// clock: hardware, or world.clock: wall), or as a member of the node's
// simulated world, whose loop runs every robot's cycles and steps the
// physics once (world/world_loop.hpp). Both do the same non-real-time work
// between runs of cycles: timed publications, delivering the topics,
// waiting for recovery after a fault.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <limits>
#include <thread>

#include <fmt/format.h>

#include "servoloop/core/logging.hpp"
#include "servoloop/core/step_grid.hpp"
#include "servoloop/node/message_json.hpp"
#include "servoloop/node/realtime_settings.hpp"
#include "servoloop/node/robot_instance.hpp"

namespace servoloop::node {
namespace {

// Simulated time between two bus flushes of a free-running loop.
constexpr double kFreeRunningFlushInterval_s = 0.01;

}  // namespace

void RobotInstance::addTimedPublication(const TimedPublication& publication) {
  if (started()) throw Error("RobotInstance: timed publications must be added before start()");
  publications_.push_back(publication);
  std::stable_sort(publications_.begin(), publications_.end(),
                   [](const auto& a, const auto& b) { return a.time_s < b.time_s; });
}

std::uint64_t RobotInstance::stepsAt(double time_s) const {
  const double steps = std::ceil(time_s / sim_loop_->physicsStep().seconds - 1e-9);
  return steps <= 0.0 ? 0 : static_cast<std::uint64_t>(steps);
}

void RobotInstance::publish(const TimedPublication& publication) {
  try {
    servoloop::node::publishJson(*bus_, publication.topic, publication.message, publication.type);
    logger().debug("published {} on '{}' at t = {} s",
                   publication.message.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace),
                   publication.topic, publication.time_s);
  } catch (const std::exception& e) {
    logger().error("timed publication on '{}' at t = {} s failed: {}", publication.topic, publication.time_s,
                   e.what());
  }
}

// Each published message is delivered (flush) before the loop goes on, so
// subscribers that hand work to the real-time side from their callback (a
// trajectory controller building its trajectory) have done so by the next
// cycle, whenever the delivery thread would have woken up.
void RobotInstance::publishDue(std::uint64_t steps_taken) {
  const std::size_t before = next_publication_;
  while (next_publication_ < publications_.size() && stepsAt(publications_[next_publication_].time_s) <= steps_taken) {
    bus_->setTime(Time(stepsToSeconds(steps_taken, sim_loop_->physicsStep().seconds)));
    publish(publications_[next_publication_++]);
  }
  if (next_publication_ != before) bus_->flush();
}

void RobotInstance::publishDueAt(double time_s) {
  const std::size_t before = next_publication_;
  while (next_publication_ < publications_.size() && publications_[next_publication_].time_s <= time_s) {
    publish(publications_[next_publication_++]);
  }
  if (next_publication_ != before) bus_->flush();
}

// On the wall clock the loop runs in pieces that end at the next timed
// publication (or the duration); each piece carries on the previous piece's
// deadline grid (WallClockLoop), and the publish between them takes a few
// microseconds of the time before the next deadline.
void RobotInstance::driveWallClockLoop(std::optional<double> duration_s) {
  const double end_s = duration_s ? *duration_s : std::numeric_limits<double>::infinity();
  const double period_s = loop_->controlPeriod().seconds;
  while (!stop_requested_.load()) {
    const double now_s = simTime();
    publishDueAt(now_s);
    if (now_s >= end_s - 0.5 * period_s || loop_->hardwareAskedToStop()) break;
    double target_s = end_s;
    if (next_publication_ < publications_.size()) target_s = std::min(target_s, publications_[next_publication_].time_s);
    if (std::isinf(target_s)) {
      loop_->run(stop_requested_);
    } else {
      loop_->runFor(Duration(std::max(target_s - now_s, period_s)));
    }
  }
}

// A run with a duration ends when the hardware stops the loop; an open-ended
// one (a node serving clients) waits in fault for `control recover`.
void RobotInstance::driveLoop(std::optional<double> duration_s) {
  for (;;) {
    driveWallClockLoop(duration_s);
    if (duration_s || stop_requested_.load() || !loop_->hardwareAskedToStop()) break;
    bus_->flush();
    if (!waitForRecovery()) break;
  }
  bus_->flush();
  loop_done_.store(true);
  if (on_finished_ && !abandoned_.load()) on_finished_();
}

void RobotInstance::start(std::optional<double> duration_s) {
  std::lock_guard lock(lifecycle_mutex_);
  if (started()) return;
  if (world_loop_ != nullptr) {
    // The world's thread runs enterWorld() (the launch controllers): before
    // add() returns when the world runs, else first thing when it starts.
    const double dt = sim_loop_->physicsStep().seconds;
    world_duration_ = duration_s.has_value();
    world_end_steps_ = duration_s ? stepsAt(*duration_s) : std::numeric_limits<std::uint64_t>::max();
    world_flush_steps_ =
        std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(kFreeRunningFlushInterval_s / dt)));
    world_started_.store(true);
    world_loop_->add(*this);
    return;
  }
  // start() returns once the launch file's controllers are running, so that
  // nobody (an IPC client, a test) sees the robot before its controllers.
  std::promise<void> launch_controllers_started;
  std::future<void> ready = launch_controllers_started.get_future();
  loop_thread_ = std::thread([this, duration_s, started = std::move(launch_controllers_started)]() mutable {
    bool started_set = false;
    try {
      // Scheduling, affinity and locked memory first: everything after runs as the loop will.
      if (!realtime_.empty()) applyRealtimeSettings(realtime_, fmt::format("robot '{}'", namespace_));
      // Before any publication: a controller's starting() forgets commands
      // published before it.
      startLaunchControllers();
      started.set_value();
      started_set = true;
      driveLoop(duration_s);
    } catch (const std::exception& e) {
      if (!started_set) started.set_value();
      logger().error("robot '{}': the control loop stopped: {}", namespace_, e.what());
      loop_done_.store(true);
      if (on_finished_) on_finished_();
    }
  });
  ready.wait();
}

void RobotInstance::stop() {
  std::lock_guard lock(lifecycle_mutex_);
  {
    std::lock_guard recovery(recovery_mutex_);
    stop_requested_.store(true);
  }
  recovery_wake_.notify_all();
  if (loop_) loop_->requestStop();
  if (loop_thread_.joinable() && !stuck_.load()) {
    // A hardware call that stops returning now is caught by the watch of
    // the thread that waits here no longer: checked every 100 ms.
    while (!loop_done_.load()) {
      watchHardware(std::chrono::steady_clock::now());
      if (stuck_.load()) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  if (loop_thread_.joinable() && stuck_.load() && !loop_done_.load()) {
    // Its hardware call never returned: the thread is left where it is,
    // and this robot with it (Node::shutdown keeps it alive).
    abandoned_.store(true);
    loop_thread_.detach();
    logger().error("robot '{}': {}; the node ends without waiting for it", namespace_, stuckReason());
    return;
  }
  if (loop_thread_.joinable()) loop_thread_.join();
  if (world_loop_ != nullptr && world_started_.load()) world_loop_->remove(*this);
  loop_done_.store(true);
}

// --- As a member of the world: the world's thread calls these ---

void RobotInstance::enterWorld() {
  // Before any publication: a controller's starting() forgets commands
  // published before it.
  startLaunchControllers();
}

void RobotInstance::finishRun() {
  bus_->flush();
  if (loop_done_.exchange(true)) return;
  if (on_finished_) on_finished_();
}

bool RobotInstance::resumeIfRecoveryRequested() {
  {
    std::lock_guard lock(recovery_mutex_);
    if (!recovery_requested_) return false;
    recovery_requested_ = false;
    // Cleared here, where the loop is sure to run again (not by recover(),
    // whose caller could otherwise see "running" for a loop that has ended).
    safety_->clearStop();
    loop_->clearHardwareStop();
    resumed_ = true;
    waiting_for_recovery_ = false;
  }
  recovery_wake_.notify_all();
  return true;
}

std::uint64_t RobotInstance::betweenSegments() {
  if (loop_done_.load() || stop_requested_.load()) return 0;
  bool waiting = false;
  {
    std::lock_guard lock(recovery_mutex_);
    waiting = waiting_for_recovery_;
  }
  if (waiting && !resumeIfRecoveryRequested()) return 0;

  const std::uint64_t taken = sim_loop_->stepsTaken();
  if (loop_->hardwareAskedToStop()) {
    // A run with a duration ends when the hardware stops the loop; an
    // open-ended one (a node serving clients) waits in fault for `control
    // recover`, while the world runs on.
    bus_->flush();
    if (world_duration_) {
      finishRun();
      return 0;
    }
    {
      std::lock_guard lock(recovery_mutex_);
      if (!waiting_for_recovery_) logger().error("robot '{}': {}", namespace_, safety_->reason());
      waiting_for_recovery_ = true;
    }
    // A recover() that came before this call is served now.
    if (!resumeIfRecoveryRequested()) return 0;
  }
  if (real_time_factor_ <= 0.0) bus_->flush();
  publishDue(taken);
  std::uint64_t contacts_due = world_end_steps_;
  if (contact_states_) contacts_due = taken + contact_states_->publishDue(taken);
  if (taken >= world_end_steps_) {
    finishRun();
    return 0;
  }
  std::uint64_t target = std::min(world_end_steps_, contacts_due);
  if (next_publication_ < publications_.size()) {
    target = std::min(target, stepsAt(publications_[next_publication_].time_s));
  }
  if (real_time_factor_ <= 0.0) target = std::min(target, taken + world_flush_steps_);
  return std::max<std::uint64_t>(target - taken, 1);
}

void RobotInstance::leaveWorld() { finishRun(); }

void RobotInstance::checkResettable() const {
  if (sim_loop_ == nullptr || sim_hw_ == nullptr) {
    throw Error(fmt::format("robot '{}' runs on {} (the wall clock); hardware cannot be reset, only a simulated world",
                            namespace_, sim_hw_ == nullptr ? "hardware" : "its own thread"));
  }
  if (manager_->switchPending()) {
    throw Error(fmt::format("robot '{}': a controller switch waits for the next cycle; reset once it is done", namespace_));
  }
}

std::string RobotInstance::resetToStart(const std::vector<std::string>& changed_parameters) {
  checkResettable();
  // What was published before the reset is delivered now, to the state it had.
  bus_->flush();
  std::vector<std::string> running;
  for (const controller_manager::ControllerSpec& controller : manager_->listControllers()) {
    if (controller.state == controller_manager::ControllerState::running) running.push_back(controller.name);
  }
  // Started again: the launch file's controllers (also one that failed) and
  // those running now, in load order.
  std::vector<std::string> to_start;
  for (const controller_manager::ControllerSpec& controller : manager_->listControllers()) {
    const bool launched =
        std::find(launch_controllers_.begin(), launch_controllers_.end(), controller.name) != launch_controllers_.end();
    const bool was_running = std::find(running.begin(), running.end(), controller.name) != running.end();
    if (launched || was_running) to_start.push_back(controller.name);
  }
  const Duration period = loop_->controlPeriod();
  if (!running.empty()) {
    controller_manager::SwitchRequest request;
    request.stop_controllers = running;
    request.strictness = controller_manager::SwitchStrictness::BEST_EFFORT;
    // No cycle runs while the world stands: this thread is the real-time
    // side, and one update carries the stop out (nothing is left to update).
    if (manager_->requestSwitch(request)) {
      manager_->update(Time(simTime()), period);
      (void)manager_->finishSwitch();
    }
  }
  std::string failures;
  // Controllers whose parameters changed read them again: loaded anew.
  for (const controller_manager::ControllerSpec& controller : manager_->listControllers()) {
    const std::string prefix = (namespace_ == "/" ? "" : namespace_) + "/" + controller.name;
    const bool changed = std::any_of(changed_parameters.begin(), changed_parameters.end(), [&](const std::string& name) {
      return name == prefix || (name.size() > prefix.size() && name.starts_with(prefix) && name[prefix.size()] == '/');
    });
    if (!changed) continue;
    controller_manager::ServiceResult reloaded = manager_->unloadController(controller.name);
    if (reloaded) reloaded = loadController(controller.name);
    if (!reloaded) {
      failures += (failures.empty() ? "" : "; ") +
                  fmt::format("controller '{}' did not load again with its new parameters: {}", controller.name,
                              reloaded.message);
    }
  }
  sim_hw_->reset();
  sim_loop_->rewind();
  if (ground_truth_) ground_truth_->restart();
  if (contact_states_) contact_states_->restart();
  bus_->setTime(Time(0.0));
  next_publication_ = 0;
  startControllersAtStart(to_start, [&](const std::vector<std::string>& controllers, const std::string& why) {
    std::string names;
    for (const std::string& name : controllers) names += (names.empty() ? "'" : ", '") + name + "'";
    failures += (failures.empty() ? "" : "; ") + fmt::format("controller(s) {} did not start again: {}", names, why);
  });
  if (!failures.empty()) logger().error("robot '{}': reset: {}", namespace_, failures);
  return failures;
}


}  // namespace servoloop::node
