#pragma once
// The base of every controller, with ros_control's lifecycle:
//   constructed --initRequest--> initialized --startRequest--> running
//   running --stopRequest--> stopped --startRequest--> running
//   running --abortRequest--> failed (a fault: exception, ReturnType::error,
//                                     non-finite command) --startRequest--> running
// The manager drives these requests; controllers implement init (through
// Controller<> or MultiInterfaceController<>), starting, update, stopping.
#include <atomic>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "servoloop/controller_manager/controller_context.hpp"
#include "servoloop/hardware_interface/actuator_interfaces.hpp"
#include "servoloop/hardware_interface/controller_info.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/core/return_type.hpp"
#include "servoloop/hardware_interface/robot_hw.hpp"
#include "servoloop/core/time.hpp"

namespace servoloop::controllers {
class Pid;  // servoloop/controllers/pid.hpp
}

namespace servoloop::controller_manager {

enum class ControllerState : std::uint8_t { constructed, initialized, running, stopped, failed };

// "initialized", "running", ... as listControllers prints them.
const char* toString(ControllerState state) noexcept;

// The value a claimed command handle is put to when its controller is stopped
// for a fault: zero for effort and velocity commands, the measured position for
// position commands (the joint holds where it is).
enum class SafeCommand : std::uint8_t { zero, hold_position };

// One command handle a controller claimed during init. Remembered so the
// manager can check the controller's output after every update (a non-finite
// command is a fault) and put it to a safe value when the controller fails.
struct ClaimedCommand {
  std::string resource;            // joint or actuator name, e.g. "joint1"
  std::string hardware_interface;  // e.g. "EffortJointInterface"
  double* command = nullptr;       // the handle's command storage (owned by the RobotHW)
  const double* position = nullptr;  // measured position of the same resource
  SafeCommand safe = SafeCommand::zero;
};

// A PID of a controller whose gains may be changed while it runs, named by its
// parameter namespace under the controller, where ros_control serves the same
// PID's dynamic_reconfigure: "pid" (joint position and velocity controllers),
// "<joint>/pid" (group position controller), "gains/<joint>" (trajectory and
// gripper controllers).
struct TunablePid {
  std::string name;
  controllers::Pid* pid = nullptr;
};

class ControllerBase {
 public:
  // Plugin kind, checked by the plugin loader before a controller type is trusted.
  static constexpr const char* kPluginKind = "controller";
  // firstNonFiniteCommand() when every claimed command is finite.
  static constexpr std::size_t kAllCommandsFinite = static_cast<std::size_t>(-1);

  ControllerBase() = default;
  virtual ~ControllerBase();
  ControllerBase(const ControllerBase&) = delete;
  ControllerBase& operator=(const ControllerBase&) = delete;

  // Non-real-time. Gets the controller's interfaces from the hardware, runs the
  // controller's init and fills claimed_resources with what it claimed, one
  // entry per interface. Returns false when the controller's init returned
  // false; throws servoloop::Error (or whatever init threw) with a message
  // naming the controller and the fix. Controller<> and
  // MultiInterfaceController<> implement it; a hand-written implementation must
  // call markInitialized() on success and may call recordClaimedCommands().
  virtual bool initRequest(hardware_interface::RobotHW* robot_hw, const ControllerContext& context,
                           std::vector<hardware_interface::InterfaceResources>& claimed_resources) = 0;

  // Real-time. Called in the cycle the controller starts, before its first
  // update (which comes in the next cycle). Must not allocate, lock or log;
  // throwing here is contained by the manager (the controller fails).
  virtual void starting(const Time& /*time*/) {}

  // Real-time. One control step; period is the control time since this
  // controller's previous update (or since starting, for the first one).
  // Return ReturnType::error to be stopped as failed, ReturnType::deactivate to
  // be stopped cleanly. Must not allocate, lock, log or throw (a throw is
  // contained: the controller fails).
  virtual ReturnType update(const Time& time, const Duration& period) = 0;

  // Real-time. Called in the cycle the controller is stopped by a switch or by
  // returning ReturnType::deactivate.
  virtual void stopping(const Time& /*time*/) {}

  // Real-time. Called when the controller is stopped for a fault, after the
  // manager has already put every claimed command to its safe value (zero
  // effort/velocity, hold position). Override to reset internal state or to
  // write safe values to outputs the manager does not know about.
  virtual void setSafeOutput() {}

  // Non-real-time. The PIDs whose gains may be changed while the controller
  // runs (Pid::setGains: taken at the PID's next computeCommand, without
  // allocating or waiting). Asked after init; the pointers stay valid as long
  // as the controller. None by default.
  virtual std::vector<TunablePid> tunablePids() { return {}; }

  // --- State (safe to read from any thread) ---
  ControllerState state() const noexcept { return state_.load(std::memory_order_acquire); }
  bool isInitialized() const noexcept { return state() != ControllerState::constructed; }
  bool isRunning() const noexcept { return state() == ControllerState::running; }
  bool isFailed() const noexcept { return state() == ControllerState::failed; }

  // --- Lifecycle requests, called by the manager on the real-time thread ---
  // Calls starting() and marks the controller running. False (nothing done) if
  // the controller is not initialized, stopped or failed. Exceptions from
  // starting() propagate and leave the state unchanged.
  bool startRequest(const Time& time);
  // Calls update(); false-free wrapper kept for symmetry with ros_control.
  ReturnType updateRequest(const Time& time, const Duration& period) {
    return update(time, period);
  }
  // Calls stopping() and marks the controller stopped. False if it was not
  // running. Exceptions from stopping() propagate after the state is set.
  bool stopRequest(const Time& time);
  // Puts every claimed command to its safe value, calls setSafeOutput()
  // (swallowing anything it throws) and marks the controller failed. Never
  // throws; allocation-free.
  void abortRequest() noexcept;

  // --- Claimed command handles (recorded at init) ---
  const std::vector<ClaimedCommand>& claimedCommands() const noexcept { return claimed_commands_; }
  // Index into claimedCommands() of the first command that is NaN or infinite,
  // or kAllCommandsFinite. Real-time safe.
  // Inline: the manager checks every controller's commands after every update.
  std::size_t firstNonFiniteCommand() const noexcept {
    for (std::size_t i = 0; i < claimed_commands_.size(); ++i) {
      if (!std::isfinite(*claimed_commands_[i].command)) return i;
    }
    return kAllCommandsFinite;
  }
  // Writes each claimed command's safe value. Real-time safe.
  void writeSafeCommands() noexcept;

 protected:
  // For initRequest implementations (non-real-time).
  void markInitialized() noexcept { state_.store(ControllerState::initialized, std::memory_order_release); }
  void clearClaimedCommands() { claimed_commands_.clear(); }

  // Records what iface's claims are (the names claimed since its claims were
  // last cleared): appends one InterfaceResources entry to claimed_resources
  // and, when the interface hands out command handles, remembers each claimed
  // handle's command storage. Non-real-time.
  template <class Interface>
  void recordClaimedCommands(Interface* iface,
                             std::vector<hardware_interface::InterfaceResources>& claimed_resources);

 private:
  std::atomic<ControllerState> state_{ControllerState::constructed};
  std::vector<ClaimedCommand> claimed_commands_;
};

namespace detail {
template <class Interface>
constexpr SafeCommand safeCommandFor() {
  if constexpr (std::is_base_of_v<hardware_interface::PositionJointInterface, Interface> ||
                std::is_base_of_v<hardware_interface::PositionActuatorInterface, Interface>) {
    return SafeCommand::hold_position;
  } else {
    return SafeCommand::zero;
  }
}

// Interfaces built on ResourceManager expose their handle type; a handle with a
// command pointer is a command handle.
template <class Interface>
concept HasCommandHandles = requires(typename Interface::Handle handle) {
  { handle.getCommandPtr() } -> std::convertible_to<double*>;
  { handle.getPositionPtr() } -> std::convertible_to<const double*>;
};
}  // namespace detail

template <class Interface>
void ControllerBase::recordClaimedCommands(
    Interface* iface, std::vector<hardware_interface::InterfaceResources>& claimed_resources) {
  hardware_interface::InterfaceResources resources{iface->name(), iface->getClaims()};
  if constexpr (detail::HasCommandHandles<Interface>) {
    for (const auto& resource : resources.resources) {
      // getHandle() claims again; the name is claimed already, so this changes nothing.
      auto handle = iface->getHandle(resource);
      claimed_commands_.push_back(ClaimedCommand{resource, iface->name(), handle.getCommandPtr(),
                                                 handle.getPositionPtr(),
                                                 detail::safeCommandFor<Interface>()});
    }
  }
  claimed_resources.push_back(std::move(resources));
}

}  // namespace servoloop::controller_manager
