#pragma once
// In-process test hardware and test controllers for the controller manager
// tests. The controllers read what to do (and where to fail) from their YAML
// parameters, so each test sets up its scenario as ros_control YAML.
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>
#include <yaml-cpp/yaml.h>

#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/controller_manager/controller_factory.hpp"
#include "servoloop/controller_manager/controller_manager.hpp"
#include "servoloop/controller_manager/multi_interface_controller.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::controller_manager::testing {

namespace hi = servoloop::hardware_interface;

// What happened, in order, across hardware and controllers ("starting:a",
// "doSwitch", "update:b", ...). Written only from the thread running update()
// (and init on the loading thread); read after that thread has stopped.
inline std::vector<std::string>& eventLog() {
  static std::vector<std::string> log;
  return log;
}

// Off in tests whose loop runs on another thread for long: nothing is logged.
inline bool& eventLogEnabled() {
  static bool enabled = true;
  return enabled;
}

inline void logEvent(std::string event) {
  if (eventLogEnabled()) eventLog().push_back(std::move(event));
}

// Three joints with state, effort, velocity (optional) and position interfaces.
class TestRobotHW : public hi::RobotHW {
 public:
  static constexpr int kJoints = 3;

  explicit TestRobotHW(bool offer_velocity = true) {
    for (int i = 0; i < kJoints; ++i) {
      const std::string name = "joint" + std::to_string(i + 1);
      hi::JointStateHandle state(name, &position[i], &velocity[i], &effort[i]);
      state_interface.registerHandle(state);
      effort_interface.registerHandle(hi::JointHandle(state, &effort_command[i]));
      velocity_interface.registerHandle(hi::JointHandle(state, &velocity_command[i]));
      position_interface.registerHandle(hi::JointHandle(state, &position_command[i]));
    }
    registerInterface(&state_interface);
    registerInterface(&effort_interface);
    if (offer_velocity) registerInterface(&velocity_interface);
    registerInterface(&position_interface);
  }

  void init(const hi::HardwareInfo&) override {}
  ReturnType read(Time, Duration) override { return ReturnType::ok; }
  ReturnType write(Time, Duration) override { return ReturnType::ok; }

  bool prepareSwitch(const std::vector<hi::ControllerInfo>& start,
                     const std::vector<hi::ControllerInfo>& stop) override {
    ++prepare_calls;
    last_prepare_start = start;
    last_prepare_stop = stop;
    return accept_switch;
  }
  ReturnType doSwitch(const std::vector<hi::ControllerInfo>& start,
                      const std::vector<hi::ControllerInfo>& stop) override {
    ++do_switch_calls;
    if (record_events) logEvent("doSwitch");
    do_switch_start_count = start.size();
    do_switch_stop_count = stop.size();
    if (do_switch_throws) throw std::runtime_error("drive 3 did not answer the mode change");
    return do_switch_result;
  }

  double position[kJoints] = {0.25, -0.5, 1.0};
  double velocity[kJoints] = {0.0, 0.0, 0.0};
  double effort[kJoints] = {0.0, 0.0, 0.0};
  double effort_command[kJoints] = {0.0, 0.0, 0.0};
  double velocity_command[kJoints] = {0.0, 0.0, 0.0};
  double position_command[kJoints] = {0.0, 0.0, 0.0};

  bool accept_switch = true;
  ReturnType do_switch_result = ReturnType::ok;  // what doSwitch returns
  bool do_switch_throws = false;
  bool record_events = true;
  int prepare_calls = 0;
  std::atomic<int> do_switch_calls{0};
  std::size_t do_switch_start_count = 0;
  std::size_t do_switch_stop_count = 0;
  std::vector<hi::ControllerInfo> last_prepare_start;
  std::vector<hi::ControllerInfo> last_prepare_stop;

  hi::JointStateInterface state_interface;
  hi::EffortJointInterface effort_interface;
  hi::VelocityJointInterface velocity_interface;
  hi::PositionJointInterface position_interface;
};

// Parameters every test controller understands:
//   joint: joint1            (or joints: [joint1, joint2])
//   output: 2.5              the command written every update
//   fail_in: init | init_false | starting | update | update_error | nan | deactivate
//   fail_after: 3            updates before update/update_error/nan/deactivate strike
//   record_events: true      append "starting:<name>" etc. to eventLog()
struct TestBehaviour {
  std::string name;
  std::vector<std::string> joints;
  double output = 1.0;
  std::string fail_in;
  int fail_after = 0;
  bool record_events = true;

  void read(const ControllerContext& context) {
    name = context.name;
    const params::Parameters& params = context.params;
    if (params["joint"]) joints.push_back(params["joint"].as<std::string>());
    if (params["joints"]) {
      for (const auto& j : params["joints"].as<std::vector<std::string>>()) joints.push_back(j);
    }
    if (params["output"]) output = params["output"].as<double>();
    if (params["fail_in"]) fail_in = params["fail_in"].as<std::string>();
    if (params["fail_after"]) fail_after = params["fail_after"].as<int>();
    if (params["record_events"]) record_events = params["record_events"].as<bool>();
  }
};

template <class Interface>
class TestController : public Controller<Interface> {
 public:
  ~TestController() override { ++destroyed(); }
  static std::atomic<int>& destroyed() {
    static std::atomic<int> count{0};
    return count;
  }

  bool init(Interface* hw, const ControllerContext& context) override {
    behaviour.read(context);
    manager_rate_hz = context.manager_update_rate_hz;
    if (behaviour.fail_in == "init") {
      throw std::runtime_error("test controller '" + context.name + "' fails in init on purpose");
    }
    if (behaviour.fail_in == "init_false") return false;
    for (const auto& joint : behaviour.joints) handles.push_back(hw->getHandle(joint));
    periods.reserve(4096);
    return true;
  }

  void starting(const Time& time) override {
    ++starting_calls;
    starting_time = time;
    if (behaviour.record_events) logEvent("starting:" + behaviour.name);
    if (behaviour.fail_in == "starting") {
      throw std::runtime_error("test controller '" + behaviour.name + "' fails in starting on purpose");
    }
  }

  ReturnType update(const Time& time, const Duration& period) override {
    ++update_calls;
    last_update_time = time;
    if (periods.size() < periods.capacity()) periods.push_back(period.seconds);
    if (behaviour.record_events) logEvent("update:" + behaviour.name);
    const bool strike = update_calls > behaviour.fail_after;
    double output = behaviour.output;
    if (strike && behaviour.fail_in == "update") {
      throw std::runtime_error("test controller '" + behaviour.name + "' fails in update on purpose");
    }
    if (strike && behaviour.fail_in == "update_error") return ReturnType::error;
    if (strike && behaviour.fail_in == "deactivate") return ReturnType::deactivate;
    if (strike && behaviour.fail_in == "nan") output = std::numeric_limits<double>::quiet_NaN();
    if constexpr (requires(typename Interface::Handle h) { h.setCommand(0.0); }) {
      for (auto& handle : handles) handle.setCommand(output);
    }
    return ReturnType::ok;
  }

  void stopping(const Time&) override {
    ++stopping_calls;
    if (behaviour.record_events) logEvent("stopping:" + behaviour.name);
  }

  void setSafeOutput() override { ++safe_output_calls; }

  TestBehaviour behaviour;
  std::vector<typename Interface::Handle> handles;
  std::vector<double> periods;  // reserved at init; update() never allocates
  double manager_rate_hz = 0.0;
  int starting_calls = 0;
  int update_calls = 0;
  int stopping_calls = 0;
  int safe_output_calls = 0;
  Time starting_time;
  Time last_update_time;
};

using EffortTestController = TestController<hi::EffortJointInterface>;
using VelocityTestController = TestController<hi::VelocityJointInterface>;
using PositionTestController = TestController<hi::PositionJointInterface>;
using StateTestController = TestController<hi::JointStateInterface>;

// Claims `joint` through effort and reads every joint through the state interface.
class MultiTestController
    : public MultiInterfaceController<hi::EffortJointInterface, hi::JointStateInterface> {
 public:
  bool init(hi::RobotHW* hw, const ControllerContext& context) override {
    saw_velocity_interface = hw->get<hi::VelocityJointInterface>() != nullptr;
    effort = hw->get<hi::EffortJointInterface>()->getHandle(context.params["joint"].as<std::string>());
    auto* states = hw->get<hi::JointStateInterface>();
    for (const auto& name : states->getNames()) states->getHandle(name);
    return true;
  }
  ReturnType update(const Time&, const Duration&) override { return ReturnType::ok; }
  hi::JointHandle effort;
  bool saw_velocity_interface = true;
};

class CountingFactory : public InProcessControllerFactory {
 public:
  CountingFactory() {
    add<EffortTestController>("test_controllers/EffortController");
    add<VelocityTestController>("test_controllers/VelocityController");
    add<PositionTestController>("test_controllers/PositionController");
    add<StateTestController>("test_controllers/StateController");
    add<MultiTestController>("test_controllers/MultiController");
  }
  void reloadLibraries() override { ++reloads; }
  int reloads = 0;
};

// Captures what servoloop::logger() writes while alive.
class LogCapture {
 public:
  LogCapture()
      : sink_(std::make_shared<spdlog::sinks::ostream_sink_mt>(stream_)), level_(spdlogLogger().level()) {
    spdlogLogger().sinks().push_back(sink_);
    if (level_ > spdlog::level::info) spdlogLogger().set_level(spdlog::level::info);
  }
  ~LogCapture() {
    auto& sinks = spdlogLogger().sinks();
    for (auto it = sinks.begin(); it != sinks.end(); ++it) {
      if (*it == sink_) {
        sinks.erase(it);
        break;
      }
    }
    spdlogLogger().set_level(level_);
  }
  std::string text() const { return stream_.str(); }

 private:
  std::ostringstream stream_;
  std::shared_ptr<spdlog::sinks::ostream_sink_mt> sink_;
  spdlog::level::level_enum level_;
};

// Calls update() in a loop on its own thread, as a control loop would:
// 20 us apart, or back to back (spin) as a free-running simulation does.
class RealtimeThread {
 public:
  RealtimeThread(ControllerManager& manager, double period_s, bool spin = false)
      : thread_([this, &manager, period_s, spin] {
          double t = 0.0;
          while (!stop_.load()) {
            t += period_s;
            manager.update(Time(t), Duration(period_s));
            cycles_.fetch_add(1);
            if (!spin) std::this_thread::sleep_for(std::chrono::microseconds(20));
          }
        }) {}
  ~RealtimeThread() { stop(); }
  void stop() {
    stop_.store(true);
    if (thread_.joinable()) thread_.join();
  }
  long cycles() const { return cycles_.load(); }

 private:
  std::atomic<bool> stop_{false};
  std::atomic<long> cycles_{0};
  std::thread thread_;
};

// A manager over TestRobotHW with parameters from inline YAML, driven by
// cycle() at `rate_hz` (time starts at 0).
class ManagerFixture {
 public:
  explicit ManagerFixture(const std::string& yaml, double rate_hz = 1000.0,
                          bool offer_velocity = true)
      : hw(offer_velocity),
        params(YAML::Load(yaml)),
        factory(std::make_shared<CountingFactory>()),
        manager(&hw, factory, ControllerManager::lookupIn(params), context(), rate_hz),
        period_s(rate_hz > 0.0 ? 1.0 / rate_hz : 0.001) {
    eventLog().clear();
    eventLogEnabled() = true;
  }

  static ControllerContext context() {
    ControllerContext c;
    c.robot_namespace = "/test_robot";
    return c;
  }

  // One control cycle at the next time step.
  void cycle() {
    ++cycles;
    time = Time(cycles * period_s);
    manager.update(time, Duration(period_s));
  }
  void cycles_n(int n) {
    for (int i = 0; i < n; ++i) cycle();
  }

  // Requests a switch and runs the cycle that carries it out.
  ServiceResult switchNow(const std::vector<std::string>& start, const std::vector<std::string>& stop,
                          SwitchStrictness strictness = SwitchStrictness::STRICT) {
    ServiceResult result = manager.requestSwitch(SwitchRequest{start, stop, strictness, false, 0.0});
    if (result && manager.switchPending()) cycle();
    return result;
  }

  template <class T>
  T* get(const std::string& name) {
    return dynamic_cast<T*>(manager.getController(name));
  }

  TestRobotHW hw;
  YAML::Node params;
  std::shared_ptr<CountingFactory> factory;
  ControllerManager manager;
  double period_s;
  long cycles = 0;
  Time time;
};

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace servoloop::controller_manager::testing
