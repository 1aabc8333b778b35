#include "bullet_simulated_world.hpp"

#include "servoloop/core/errors.hpp"

namespace servoloop::sim_bullet {

void BulletSimulatedWorld::init(const hardware_interface::SimulatedWorldSettings& settings) {
  if (scene_) throw Error("bullet world: init() called twice");
  SceneSettings scene;
  scene.gravity = Eigen::Vector3d(settings.gravity[0], settings.gravity[1], settings.gravity[2]);
  scene.time_step_s = settings.time_step_s;
  scene.ground_plane = settings.ground_plane;
  scene_ = std::make_unique<BulletScene>(scene);
  settings_ = settings;
}

ReturnType BulletSimulatedWorld::step() noexcept {
  if (!scene_) return ReturnType::error;
  scene_->step();
  return ReturnType::ok;
}

void BulletSimulatedWorld::restart() {
  if (scene_) scene_->restart();
}

}  // namespace servoloop::sim_bullet
