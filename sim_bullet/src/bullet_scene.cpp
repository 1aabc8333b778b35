#include "servoloop/sim_bullet/bullet_scene.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include <BulletCollision/CollisionDispatch/btManifoldResult.h>

#include "bullet_scene_core.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::sim_bullet {
namespace detail {
namespace {

constexpr int kSolverIterations = 50;
// The most Jacobian entries (doubles, in each of the solver's two
// row-by-coordinate arrays) reserveForMember makes room for: 128 MiB each.
constexpr std::int64_t kMaxReservedJacobianEntries = std::int64_t{1} << 24;
// The ground plane's friction: above any body's, so that the smaller of the
// two coefficients of a contact with the ground is the body's own.
constexpr double kGroundFriction = 1e9;

double surfaceFriction(const btCollisionObjectWrapper* wrapper, int child) {
  const btCollisionObject* object = wrapper->getCollisionObject();
  const auto* per_child = static_cast<const std::vector<double>*>(object->getUserPointer());
  if (per_child != nullptr && child >= 0 && child < static_cast<int>(per_child->size())) {
    return (*per_child)[static_cast<std::size_t>(child)];
  }
  return object->getFriction();
}

// Bullet calls this for each contact point it adds between two colliders of
// which one is flagged CF_CUSTOM_MATERIAL_CALLBACK; `index` is the compound
// child in contact (-1 for a shape that is not a compound).
bool smallerFriction(btManifoldPoint& point, const btCollisionObjectWrapper* object0, int /*part0*/, int index0,
                     const btCollisionObjectWrapper* object1, int /*part1*/, int index1) {
  point.m_combinedFriction = std::min(surfaceFriction(object0, index0), surfaceFriction(object1, index1));
  return true;
}

}  // namespace

namespace {

// Bullet's contact callback is one process-wide pointer, and a process may
// hold two copies of this code (a program linking the engine beside the
// bullet plugin it loads, then unloads): each scene makes sure, before it
// steps, that the pointer is this copy's, never one left behind by an
// unloaded plugin. Atomic, as scenes step on several threads (Bullet reads it
// from inside its step only).
void ensureSceneFriction() noexcept {
  std::atomic_ref<ContactAddedCallback> callback(gContactAddedCallback);
  if (callback.load(std::memory_order_relaxed) != &smallerFriction) {
    callback.store(&smallerFriction, std::memory_order_relaxed);
  }
}

}  // namespace

void useSceneFriction(btCollisionObject& collider) {
  collider.setCollisionFlags(collider.getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
  ensureSceneFriction();
}

SceneCore::SceneCore(const SceneSettings& scene_settings) : settings(scene_settings) {
  if (!(settings.time_step_s > 0.0) || !std::isfinite(settings.time_step_s)) {
    throw ConfigError("Bullet world: time step " + std::to_string(settings.time_step_s) +
                      " s must be a positive, finite time");
  }
  if (!settings.gravity.allFinite()) throw ConfigError("Bullet world: gravity must be three finite numbers (m/s²)");
  collision_config = std::make_unique<btDefaultCollisionConfiguration>();
  dispatcher = std::make_unique<btCollisionDispatcher>(collision_config.get());
  broadphase = std::make_unique<btDbvtBroadphase>();
  solver = std::make_unique<SceneSolver>();
  world = std::make_unique<btMultiBodyDynamicsWorld>(dispatcher.get(), broadphase.get(), solver.get(),
                                                     collision_config.get());
  world->setGravity(btVector3(settings.gravity.x(), settings.gravity.y(), settings.gravity.z()));
  world->getSolverInfo().m_numIterations = kSolverIterations;
  if (settings.ground_plane) {
    ground_shape = std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0.0);
    ground = std::make_unique<btCollisionObject>();
    ground->setCollisionShape(ground_shape.get());
    ground->setFriction(kGroundFriction);
    world->addCollisionObject(ground.get(), int(btBroadphaseProxy::StaticFilter),
                              int(btBroadphaseProxy::AllFilter) ^ int(btBroadphaseProxy::StaticFilter));
  }
}

void SceneSolver::reserveRows(int rows, int jacobian_width, int coordinates) {
  m_data.m_jacobians.reserve(rows * jacobian_width);
  m_data.m_deltaVelocitiesUnitImpulse.reserve(rows * jacobian_width);
  m_data.m_deltaVelocities.reserve(coordinates);
  m_multiBodyNonContactConstraints.reserve(rows);
  m_multiBodyNormalContactConstraints.reserve(rows);
  m_multiBodyFrictionContactConstraints.reserve(2 * rows);
  m_tmpSolverBodyPool.reserve(rows);
  m_tmpSolverContactConstraintPool.reserve(rows);
  m_tmpSolverNonContactConstraintPool.reserve(rows);
  m_tmpSolverContactFrictionConstraintPool.reserve(2 * rows);
  m_orderTmpConstraintPool.reserve(rows);
  m_orderNonContactConstraintPool.reserve(rows);
  m_orderFrictionConstraintPool.reserve(2 * rows);
}

void SceneCore::reserveForMember(int bodies, int degrees_of_freedom) {
  // Per body, room for contacts with a few neighbours (four points each, a
  // normal row and two friction rows per point) and its joint's motor,
  // limit and friction rows.
  constexpr std::int64_t kRowsPerBody = 4 * 4 * 3 + 3;
  reserved_bodies += bodies;
  largest_dofs = std::max(largest_dofs, degrees_of_freedom);
  total_dofs += 6 + degrees_of_freedom;
  // A row's Jacobian spans both multibodies it couples: 6 + dofs each. Rows
  // times width grows with the square of the scene's size (past int's range
  // from some 4,600 bodies), so it is worked out in 64 bits and the rows held
  // to kMaxReservedJacobianEntries: a scene that large grows the arrays on
  // the steps that need more (the rare step that allocates) rather than
  // reserving gigabytes up front.
  const std::int64_t width = 2 * (6 + std::int64_t{largest_dofs});
  const std::int64_t rows =
      std::min(std::int64_t{reserved_bodies} * kRowsPerBody, kMaxReservedJacobianEntries / width);
  solver->reserveRows(static_cast<int>(rows), static_cast<int>(width), total_dofs);
}

void SceneCore::rebuildBroadphase() {
  btCollisionObjectArray& objects = world->getCollisionObjectArray();
  struct Filter {
    int group;
    int mask;
  };
  std::vector<Filter> filters;
  filters.reserve(static_cast<std::size_t>(objects.size()));
  // Each proxy out of the old broadphase, its pairs (and their contact
  // manifolds) released through the dispatcher.
  for (int i = 0; i < objects.size(); ++i) {
    btCollisionObject& object = *objects[i];
    btBroadphaseProxy* proxy = object.getBroadphaseHandle();
    filters.push_back({proxy->m_collisionFilterGroup, proxy->m_collisionFilterMask});
    broadphase->getOverlappingPairCache()->cleanProxyFromPairs(proxy, dispatcher.get());
    broadphase->destroyProxy(proxy, dispatcher.get());
    object.setBroadphaseHandle(nullptr);
  }
  auto fresh = std::make_unique<btDbvtBroadphase>();
  world->setBroadphase(fresh.get());
  broadphase = std::move(fresh);
  for (int i = 0; i < objects.size(); ++i) {
    btCollisionObject& object = *objects[i];
    btVector3 aabb_min;
    btVector3 aabb_max;
    object.getCollisionShape()->getAabb(object.getWorldTransform(), aabb_min, aabb_max);
    const Filter filter = filters[static_cast<std::size_t>(i)];
    object.setBroadphaseHandle(broadphase->createProxy(aabb_min, aabb_max,
                                                       object.getCollisionShape()->getShapeType(), &object,
                                                       filter.group, filter.mask, dispatcher.get()));
  }
}

SceneCore::~SceneCore() {
  if (ground) world->removeCollisionObject(ground.get());
}

}  // namespace detail

BulletScene::BulletScene(const SceneSettings& settings) : core_(std::make_unique<detail::SceneCore>(settings)) {}

BulletScene::~BulletScene() = default;

void BulletScene::step() {
  detail::SceneCore& scene = *core_;
  detail::ensureSceneFriction();
  for (detail::SceneMember* member : scene.members) member->beforeSceneStep();
  // maxSubSteps = 0: exactly one step of time_step_s, no interpolation.
  scene.world->stepSimulation(scene.settings.time_step_s, 0, scene.settings.time_step_s);
  for (detail::SceneMember* member : scene.members) member->afterSceneStep();
  ++scene.steps;
}

void BulletScene::restart() {
  detail::SceneCore& scene = *core_;
  scene.rebuildBroadphase();
  scene.solver->reset();  // its random seed (unused by the default solver order) back to the start
  scene.steps = 0;
}

double BulletScene::time() const { return static_cast<double>(core_->steps) * core_->settings.time_step_s; }
double BulletScene::timeStep() const { return core_->settings.time_step_s; }
const SceneSettings& BulletScene::settings() const { return core_->settings; }
std::size_t BulletScene::numMembers() const { return core_->members.size(); }

}  // namespace servoloop::sim_bullet
