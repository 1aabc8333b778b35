#pragma once
// One Bullet world that several robots and objects share: one dynamics world,
// one ground plane, one gravity and time step, contacts between every body in
// it. Each robot is a BulletWorld built into the scene; the scene's step()
// advances all of them at once. No Bullet type appears here (pimpl).
//
//   BulletScene scene({.gravity = {0, 0, -9.81}, .time_step_s = 0.001, .ground_plane = true});
//   BulletWorld cart(cart_model, cart_settings, scene);
//   BulletWorld box(box_model, box_settings, scene);
//   cart.setJointEffort(0, 1.0);   // commands of every member for the next step
//   scene.step();                  // one step of the whole scene
//
// Contact friction between two bodies is the smaller of their coefficients,
// as in Gazebo (ODE); the ground plane's is unbounded, so a contact with it
// takes the body's own.
//
// Threading: construction, adding and removing members (building or
// destroying a BulletWorld on the scene) are non-real-time and
// must not overlap step(); step() is real-time safe once every member is built.
#include <cstddef>
#include <cstdint>
#include <memory>

#include <Eigen/Core>

namespace servoloop::sim_bullet {

namespace detail {
struct SceneCore;  // bullet_scene_core.hpp
}

struct SceneSettings {
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};  // m/s², world frame
  double time_step_s{0.001};                 // one solver step per step()
  bool ground_plane{false};                  // static plane z = 0 (normal +z)
};

class BulletScene {
 public:
  // Throws ConfigError for a time step that is not a positive finite number
  // or a gravity that is not finite.
  explicit BulletScene(const SceneSettings& settings = {});
  // The members must be destroyed first.
  ~BulletScene();
  BulletScene(const BulletScene&) = delete;
  BulletScene& operator=(const BulletScene&) = delete;

  // Real-time. Every member's commands of this step applied (efforts,
  // damping), one step of time_step_s for the whole scene, then every
  // member's applied efforts read back.
  void step();

  // Non-real-time, not during step(), with every member back at its start
  // pose (BulletWorld::reset): the scene forgets what it carried from step to
  // step (contact points and their warm-start impulses, the broadphase's
  // pairs and tree) and its time is 0, so that the steps that follow are
  // those of a scene just built with its bodies where they are now: the same
  // inputs give bit-identical results.
  void restart();

  double time() const;  // s since construction or restart()
  double timeStep() const;
  const SceneSettings& settings() const;
  std::size_t numMembers() const;

  detail::SceneCore& core() noexcept { return *core_; }

 private:
  std::unique_ptr<detail::SceneCore> core_;
};

}  // namespace servoloop::sim_bullet
