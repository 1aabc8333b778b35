#pragma once
// What BulletWorld::deepestMemberOverlap asks Bullet's contact test: the
// deepest contact of one of a robot's colliders with another member of the
// scene, and the URDF link of a compound child for its message.
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <btBulletCollisionCommon.h>

namespace servoloop::sim_bullet::detail {

// The deepest contact of one collider with colliders outside `own`, with
// the compound child in contact on each side.
struct OverlapProbe final : btCollisionWorld::ContactResultCallback {
  const std::vector<std::unique_ptr<btMultiBodyLinkCollider>>* own = nullptr;
  const btCollisionObject* ground = nullptr;
  double depth_m = 0.0;
  int own_child = -1;
  const btCollisionObject* other = nullptr;
  int other_child = -1;

  bool ours(const btCollisionObject* object) const {
    return std::any_of(own->begin(), own->end(), [&](const auto& c) { return c.get() == object; });
  }

  btScalar addSingleResult(btManifoldPoint& point, const btCollisionObjectWrapper* a, int /*part0*/, int index0,
                           const btCollisionObjectWrapper* b, int /*part1*/, int index1) override {
    const bool first_ours = ours(a->getCollisionObject());
    const btCollisionObject* foreign = first_ours ? b->getCollisionObject() : a->getCollisionObject();
    if (ours(foreign) || foreign == ground) return 0;
    const double depth = -point.getDistance();
    if (depth > depth_m) {
      depth_m = depth;
      other = foreign;
      own_child = first_ours ? index0 : index1;
      other_child = first_ours ? index1 : index0;
    }
    return 0;
  }
};

inline const std::string& childLink(const std::vector<std::string>& child_links, int child) {
  static const std::string unknown = "?";
  if (child >= 0 && child < static_cast<int>(child_links.size())) return child_links[static_cast<std::size_t>(child)];
  return child_links.size() == 1 ? child_links.front() : unknown;
}

}  // namespace servoloop::sim_bullet::detail
