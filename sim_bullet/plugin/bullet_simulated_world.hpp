#pragma once
// The "bullet/world" plugin: one BulletScene that every robot of a node on
// the bullet backend is built into, so that they touch each other.
#include <memory>

#include "servoloop/hardware_interface/simulated_world.hpp"
#include "servoloop/sim_bullet/bullet_scene.hpp"

namespace servoloop::sim_bullet {

class BulletSimulatedWorld final : public hardware_interface::SimulatedWorld {
 public:
  void init(const hardware_interface::SimulatedWorldSettings& settings) override;
  const hardware_interface::SimulatedWorldSettings& settings() const noexcept override { return settings_; }
  bool robotsTouch() const noexcept override { return true; }
  ReturnType step() noexcept override;
  void restart() override;

  // The scene robots build into; null before init().
  BulletScene* scene() noexcept { return scene_.get(); }

 private:
  hardware_interface::SimulatedWorldSettings settings_;
  std::unique_ptr<BulletScene> scene_;
};

}  // namespace servoloop::sim_bullet
