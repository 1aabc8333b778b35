#pragma once
// Test doubles for the control loop tests: a simulated robot with one joint
// (a unit inertia driven by its effort command) that records every call, and
// a controller that records its updates. The record is a preallocated buffer,
// so recording never allocates (the allocation test uses the same doubles).
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "servoloop/controller_manager/control_loop.hpp"
#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/controller_manager/controller_factory.hpp"
#include "servoloop/controller_manager/controller_manager.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/hardware_interface/simulated_robot_hw.hpp"

namespace servoloop::controller_manager::testing {

namespace hi = servoloop::hardware_interface;

enum class EventKind { read, update, hook, write, step };

inline const char* toString(EventKind kind) {
  switch (kind) {
    case EventKind::read: return "read";
    case EventKind::update: return "update";
    case EventKind::hook: return "hook";
    case EventKind::write: return "write";
    case EventKind::step: return "step";
  }
  return "?";
}

struct Event {
  EventKind kind;
  double time_s;
  double period_s;  // the period the call was given (0 for step)
  double command;   // write: the effort command the hardware saw
};

// Fixed-capacity event log; events beyond the capacity are dropped (counted).
class EventRecorder {
 public:
  explicit EventRecorder(std::size_t capacity = 1 << 16) { events_.reserve(capacity); }
  void add(EventKind kind, double time_s, double period_s, double command = 0.0) noexcept {
    if (!enabled) return;
    if (events_.size() < events_.capacity()) {
      events_.push_back(Event{kind, time_s, period_s, command});
    } else {
      ++dropped_;
    }
  }
  void clear() noexcept {
    events_.clear();
    dropped_ = 0;
  }
  const std::vector<Event>& events() const { return events_; }
  std::vector<Event> ofKind(EventKind kind) const {
    std::vector<Event> out;
    for (const Event& e : events_) {
      if (e.kind == kind) out.push_back(e);
    }
    return out;
  }
  std::string sequence() const {
    std::string out;
    for (const Event& e : events_) {
      if (!out.empty()) out += ' ';
      out += toString(e.kind);
    }
    return out;
  }
  std::size_t dropped() const { return dropped_; }
  bool enabled = true;

 private:
  std::vector<Event> events_;
  std::size_t dropped_ = 0;
};

// One joint "joint1": unit inertia, effort-driven, integrated by step()
// (semi-implicit Euler). Calls in [fail_from, fail_until) of read/write/step
// (counted per call kind from 0) return the configured result; reads in
// [nan_position_from, nan_position_until) report a NaN position.
class FakeSimulatedRobotHW : public hi::SimulatedRobotHW {
 public:
  static constexpr std::uint64_t kNever = std::numeric_limits<std::uint64_t>::max();

  struct Script {
    std::uint64_t from = kNever;
    std::uint64_t until = kNever;
    ReturnType result = ReturnType::error;
    ReturnType at(std::uint64_t call) const {
      return call >= from && call < until ? result : ReturnType::ok;
    }
  };

  FakeSimulatedRobotHW(double time_step_s, EventRecorder* recorder)
      : time_step_s_(time_step_s), recorder_(recorder) {
    hi::JointStateHandle state("joint1", &position, &velocity, &effort);
    state_interface.registerHandle(state);
    effort_interface.registerHandle(hi::JointHandle(state, &effort_command));
    registerInterface(&state_interface);
    registerInterface(&effort_interface);
  }

  void init(const hi::HardwareInfo&) override {}

  ReturnType read(Time time, Duration period) override {
    if (recorder_ != nullptr) recorder_->add(EventKind::read, time.seconds, period.seconds);
    if (read_sleep.count() > 0) std::this_thread::sleep_for(read_sleep);
    effort = effort_command;
    // A NaN reading lasts one read: the joint's own position comes back at the next.
    if (reported_nan_) position = position_before_nan_;
    reported_nan_ = reads >= nan_position_from && reads < nan_position_until;
    if (reported_nan_) {
      position_before_nan_ = position;
      position = std::numeric_limits<double>::quiet_NaN();
    }
    return read_script.at(reads++);
  }
  ReturnType write(Time time, Duration period) override {
    if (recorder_ != nullptr) recorder_->add(EventKind::write, time.seconds, period.seconds, effort_command);
    applied_effort = effort_command;
    return write_script.at(writes++);
  }
  Duration timeStep() const override { return Duration(time_step_s_); }
  ReturnType step() override {
    if (recorder_ != nullptr) recorder_->add(EventKind::step, simTime().seconds, 0.0);
    if (steps == stall_at_step) std::this_thread::sleep_for(stall);
    velocity += applied_effort * time_step_s_;
    position += velocity * time_step_s_;
    return step_script.at(steps++);
  }
  Time simTime() const override { return Time(static_cast<double>(steps) * time_step_s_); }
  void reset() override {
    steps = reads = writes = 0;
    position = velocity = effort = effort_command = applied_effort = 0.0;
    reported_nan_ = false;
  }
  void setEmergencyStop(bool) override {}

  double position = 0.0;
  double velocity = 0.0;
  double effort = 0.0;
  double effort_command = 0.0;
  double applied_effort = 0.0;  // what the last write() sent to the "motor"

  std::uint64_t steps = 0;
  std::uint64_t reads = 0;
  std::uint64_t writes = 0;
  Script read_script;
  // Reads in [nan_position_from, nan_position_until) (counted from 0) report a
  // NaN position and return ok, as a driver that lost its encoder might.
  std::uint64_t nan_position_from = kNever;
  std::uint64_t nan_position_until = kNever;
  Script write_script;
  Script step_script;
  std::chrono::microseconds read_sleep{0};
  std::uint64_t stall_at_step = kNever;  // step() sleeps `stall` once, at this step
  std::chrono::milliseconds stall{0};

  hi::JointStateInterface state_interface;
  hi::EffortJointInterface effort_interface;

 private:
  double time_step_s_;
  EventRecorder* recorder_;
  bool reported_nan_ = false;         // the last read() reported a NaN position
  double position_before_nan_ = 0.0;  // the position it hid
};

// Writes `output` (parameter, default 2.5) to `joint` every update and
// records the update's time and period.
class RecordingController : public Controller<hi::EffortJointInterface> {
 public:
  explicit RecordingController(EventRecorder* recorder) : recorder_(recorder) {}

  bool init(hi::EffortJointInterface* hw, const ControllerContext& context) override {
    joint_ = hw->getHandle(context.params["joint"].as<std::string>());
    if (context.params["output"]) output_ = context.params["output"].as<double>();
    return true;
  }
  ReturnType update(const Time& time, const Duration& period) override {
    ++updates;
    if (recorder_ != nullptr) recorder_->add(EventKind::update, time.seconds, period.seconds);
    joint_.setCommand(output_);
    return ReturnType::ok;
  }

  std::uint64_t updates = 0;

 private:
  EventRecorder* recorder_;
  hi::JointHandle joint_;
  double output_ = 2.5;
};

// Records every hook call.
class RecordingHook : public LoopCycleHook {
 public:
  explicit RecordingHook(EventRecorder* recorder) : recorder_(recorder) {}
  void afterUpdate(const Time& time, const Duration& period) noexcept override {
    ++calls;
    recorder_->add(EventKind::hook, time.seconds, period.seconds);
  }
  std::uint64_t calls = 0;

 private:
  EventRecorder* recorder_;
};

// Fake hardware + a manager (at manager_rate_hz; 0: no fixed rate) with one
// loaded RecordingController "ctrl" on joint1.
struct LoopFixture {
  explicit LoopFixture(double time_step_s = 0.001, double manager_rate_hz = 0.0,
                       EventRecorder* record_into = nullptr)
      : recorder(record_into != nullptr ? record_into : &own_recorder),
        hw(time_step_s, recorder),
        factory(std::make_shared<InProcessControllerFactory>()),
        params(YAML::Load("ctrl: {type: test/RecordingController, joint: joint1, output: 2.5}")),
        manager(&hw, factory, ControllerManager::lookupIn(params), context(), manager_rate_hz) {
    EventRecorder* r = recorder;
    factory->add("test/RecordingController", [r] {
      return ControllerPtr(new RecordingController(r), [](ControllerBase* c) { delete c; });
    });
    const ServiceResult loaded = manager.loadController("ctrl");
    if (!loaded) throw std::runtime_error("test fixture: " + loaded.message);
  }

  static ControllerContext context() {
    ControllerContext c;
    c.robot_namespace = "/loop_test_robot";
    return c;
  }

  // Hands the start of "ctrl" to the manager; the loop's next update carries it out.
  void requestStart() {
    const ServiceResult requested =
        manager.requestSwitch(SwitchRequest{{"ctrl"}, {}, SwitchStrictness::STRICT, false, 0.0});
    if (!requested) throw std::runtime_error("test fixture: " + requested.message);
  }

  RecordingController* controller() { return dynamic_cast<RecordingController*>(manager.getController("ctrl")); }

  EventRecorder own_recorder;
  EventRecorder* recorder;
  FakeSimulatedRobotHW hw;
  std::shared_ptr<InProcessControllerFactory> factory;
  YAML::Node params;
  ControllerManager manager;
};

}  // namespace servoloop::controller_manager::testing
