#pragma once
// The physics world a node's simulated robots share. A simulation backend
// that lets robots touch registers one (plugin kind "sim_world", type
// "<backend>/world"); each robot's SimulatedRobotHW joins it before its
// init() and builds its bodies into it. The node's world loop then runs every
// robot's cycle (read, controllers, write, the robot's step(), which hands
// its commands over) and steps the world once, so all robots see the same
// step's state.
//
// A backend without one simulates each robot apart: SeparateWorlds stands in,
// and each robot's step() advances its own physics.
//
// Threading: init() and the robots' joining are non-real-time and must not
// overlap step(); step() is real-time: no allocation, no locks, no logging,
// no exceptions.
#include <array>

#include "servoloop/core/return_type.hpp"
#include "servoloop/core/time.hpp"

namespace servoloop::hardware_interface {

// What every body of one world shares.
struct SimulatedWorldSettings {
  double time_step_s = 0.001;                      // one physics step, s
  std::array<double, 3> gravity{0.0, 0.0, -9.81};  // m/s², world frame
  bool ground_plane = false;                       // static plane z = 0, normal +z
};

class SimulatedWorld {
 public:
  static constexpr const char* kPluginKind = "sim_world";

  virtual ~SimulatedWorld() = default;

  // Non-real-time, once, before any robot joins. Throws servoloop::ConfigError
  // for settings the world cannot simulate.
  virtual void init(const SimulatedWorldSettings& settings) = 0;
  virtual const SimulatedWorldSettings& settings() const noexcept = 0;

  // Whether the robots of this world touch each other (one physics world);
  // false when each is simulated apart.
  virtual bool robotsTouch() const noexcept = 0;

  // Real-time. One physics step of everything the robots share, after every
  // robot's cycle of this step (their commands handed over by their step()).
  virtual ReturnType step() noexcept = 0;

  // Non-real-time, never during step(): after every robot of the world was
  // reset (SimulatedRobotHW::reset), the world forgets what it carried from
  // step to step (contact caches, its broadphase) and its own time restarts,
  // so that the steps that follow are those of a world just built with its
  // bodies where they are now. The node calls it before the world's first
  // step too, so that a reset world and a new one step alike. Nothing by
  // default (a world that carries nothing between steps).
  virtual void restart() {}
};

// Robots simulated apart, each advancing its own physics in its step(): the
// world of a backend that has no shared one.
class SeparateWorlds final : public SimulatedWorld {
 public:
  void init(const SimulatedWorldSettings& settings) override { settings_ = settings; }
  const SimulatedWorldSettings& settings() const noexcept override { return settings_; }
  bool robotsTouch() const noexcept override { return false; }
  ReturnType step() noexcept override { return ReturnType::ok; }

 private:
  SimulatedWorldSettings settings_;
};

}  // namespace servoloop::hardware_interface
