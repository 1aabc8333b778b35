#pragma once
// The parts of a BulletScene its members (BulletWorld) build into: Bullet's
// dynamics world, the ground plane and the list of members the scene steps.
#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <btBulletCollisionCommon.h>

#include "servoloop/sim_bullet/bullet_scene.hpp"

namespace servoloop::sim_bullet::detail {

// One robot or object of a scene, as the scene steps and resets it.
class SceneMember {
 public:
  virtual ~SceneMember() = default;
  // Real-time. Before the scene's step: the member's joint efforts of this step.
  virtual void beforeSceneStep() noexcept = 0;
  // Real-time. After it: what the member's actuators applied, commands cleared.
  virtual void afterSceneStep() noexcept = 0;
};

// Every collider of a scene is flagged for Bullet's contact-added callback,
// which sets the contact's friction to the smaller of the two surfaces'
// coefficients (Gazebo's rule): a collider's own coefficient, or with
// `per-child friction` in its user pointer (a std::vector<double>), that of
// the compound child in contact. Call on every collider added to a scene.
void useSceneFriction(btCollisionObject& collider);

// Bullet's multibody solver with its working arrays sized ahead: they only
// ever grow, each time a step meets more constraint rows than any before
// (more contacts, a larger island), and growing allocates on the real-time
// path. reserveRows() makes room while members are added.
class SceneSolver final : public btMultiBodyConstraintSolver {
 public:
  // Room for `rows` constraint rows whose Jacobians span at most
  // `jacobian_width` coordinates, over `coordinates` coordinates in all.
  void reserveRows(int rows, int jacobian_width, int coordinates);
};

struct SceneCore {
  explicit SceneCore(const SceneSettings& scene_settings);
  ~SceneCore();
  SceneCore(const SceneCore&) = delete;
  SceneCore& operator=(const SceneCore&) = delete;

  SceneSettings settings;
  // Bullet objects, destroyed in reverse order of creation.
  std::unique_ptr<btDefaultCollisionConfiguration> collision_config;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  std::unique_ptr<btDbvtBroadphase> broadphase;
  std::unique_ptr<SceneSolver> solver;
  std::unique_ptr<btMultiBodyDynamicsWorld> world;
  std::unique_ptr<btStaticPlaneShape> ground_shape;
  std::unique_ptr<btCollisionObject> ground;  // null without a ground plane
  // In the order they joined; the scene steps them in this order.
  std::vector<SceneMember*> members;
  // Whose each member's collider is, for messages: the robot, the URDF link
  // of each child of its compound shape, and that child's name as Gazebo
  // scopes it for contact sensors ("robot::link::link_collision").
  struct ColliderOwner {
    std::string robot;
    std::vector<std::string> child_links;
    std::vector<std::string> collision_names;
  };
  std::unordered_map<const btCollisionObject*, ColliderOwner> collider_owners;
  std::uint64_t steps = 0;

  // Non-real-time: a new broadphase holding every collision object, in the
  // world's order, with its filter, and no contact manifold (BulletScene::restart).
  void rebuildBroadphase();

  // Non-real-time, for each member joining: room in the solver for the
  // contacts and joint rows the scene may meet (SceneSolver).
  void reserveForMember(int bodies, int degrees_of_freedom);
  int reserved_bodies = 0;
  int largest_dofs = 0;
  int total_dofs = 0;
};

}  // namespace servoloop::sim_bullet::detail
