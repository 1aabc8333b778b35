#include "servoloop/sim_common/collision_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include <Eigen/Geometry>
#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <LinearMath/btConvexHullComputer.h>

#include "servoloop/core/errors.hpp"

namespace servoloop::sim_common {
namespace {

// Points closer than this to the line or plane of the others (relative to the
// mesh's size) span no length, area or volume.
constexpr double kFlatTolerance = 1e-9;

// Directions the thinning of a large hull measures its extent in.
constexpr std::size_t kThinningDirections = 2000;

std::size_t farthestFrom(const std::vector<Eigen::Vector3d>& points, const auto& distance) {
  std::size_t best = 0;
  double best_distance = -1.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double d = distance(points[i]);
    if (d > best_distance) {
      best_distance = d;
      best = i;
    }
  }
  return best;
}

}  // namespace

std::vector<Eigen::Vector3d> readMeshVertices(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw ConfigError(path + ": cannot read the mesh: no such file; check the path and permissions");
  }
  Assimp::Importer importer;
  // ROS robots' frames are Z-up; assimp would turn a COLLADA file to Y-up.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  // Lines and points carry no volume; only triangles and polygons are read.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_PreTransformVertices | aiProcess_SortByPType | aiProcess_JoinIdenticalVertices);
  if (scene == nullptr) {
    throw ConfigError(path + ": not a mesh assimp can read (" + importer.GetErrorString() +
                      "); export the collision mesh as STL, COLLADA (.dae) or OBJ");
  }
  std::vector<Eigen::Vector3d> vertices;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      vertices.emplace_back(p.x, p.y, p.z);
    }
  }
  if (vertices.empty()) {
    throw ConfigError(path + ": the mesh holds no triangles; export the collision mesh with its faces");
  }
  for (const auto& v : vertices) {
    if (!v.allFinite()) {
      throw ConfigError(path + ": the mesh has a vertex that is not a finite number; export the collision mesh again");
    }
  }
  return vertices;
}

std::vector<Eigen::Vector3d> convexHullVertices(const std::vector<Eigen::Vector3d>& points, std::size_t max_vertices,
                                                const std::string& what) {
  const auto flat = [&] {
    return ConfigError(what + " spans no volume (its points lie in a plane or on a line), so it has no convex hull "
                              "to collide with; give it thickness or use a <box>");
  };
  if (points.size() < 4) throw flat();
  // Four points as far apart as the set allows: the first corners kept, and
  // the test for a set that spans no volume.
  const Eigen::Vector3d& first = points[farthestFrom(points, [&](const Eigen::Vector3d& p) { return p.x(); })];
  const Eigen::Vector3d a = points[farthestFrom(points, [&](const Eigen::Vector3d& p) { return (p - first).norm(); })];
  const Eigen::Vector3d b = points[farthestFrom(points, [&](const Eigen::Vector3d& p) { return (p - a).norm(); })];
  const double size = (b - a).norm();
  const Eigen::Vector3d line = (b - a).normalized();
  const Eigen::Vector3d c = points[farthestFrom(points, [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = p - a;
    return (d - d.dot(line) * line).norm();
  })];
  const Eigen::Vector3d normal = line.cross(c - a);
  if (!(size > 0.0) || normal.norm() <= kFlatTolerance * size * size) throw flat();
  const Eigen::Vector3d unit_normal = normal.normalized();
  const double depth = std::abs((points[farthestFrom(points, [&](const Eigen::Vector3d& p) {
                                   return std::abs((p - a).dot(unit_normal));
                                 })] -
                                 a)
                                    .dot(unit_normal));
  if (depth <= kFlatTolerance * size) throw flat();

  std::vector<double> coordinates;
  coordinates.reserve(points.size() * 3);
  for (const auto& p : points) coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
  btConvexHullComputer hull;
  hull.compute(coordinates.data(), 3 * static_cast<int>(sizeof(double)), static_cast<int>(points.size()), 0.0, 0.0);
  std::vector<Eigen::Vector3d> corners;
  corners.reserve(static_cast<std::size_t>(hull.original_vertex_index.size()));
  // The hull computer rounds its vertices (it works on integers inside); the
  // input points they stand for are exact.
  for (int i = 0; i < hull.original_vertex_index.size(); ++i) {
    corners.push_back(points[static_cast<std::size_t>(hull.original_vertex_index[i])]);
  }
  if (corners.size() <= max_vertices) return corners;

  // Thin greedily: over a fine, even spread of directions, the hull's extent
  // in each direction is its farthest corner; keep adding the corner of the
  // direction whose extent the kept corners fall shortest of. The kept hull
  // then reaches as close to the full one, in every direction, as the
  // budget allows.
  std::vector<Eigen::Vector3d> directions(kThinningDirections);
  const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
  for (std::size_t i = 0; i < kThinningDirections; ++i) {
    const double z = 1.0 - (2.0 * static_cast<double>(i) + 1.0) / static_cast<double>(kThinningDirections);
    const double r = std::sqrt(1.0 - z * z);
    directions[i] = Eigen::Vector3d(r * std::cos(golden_angle * static_cast<double>(i)),
                                    r * std::sin(golden_angle * static_cast<double>(i)), z);
  }
  std::vector<std::size_t> support(kThinningDirections);
  std::vector<double> reach(kThinningDirections), kept_reach(kThinningDirections, -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < kThinningDirections; ++i) {
    support[i] = farthestFrom(corners, [&](const Eigen::Vector3d& p) { return p.dot(directions[i]); });
    reach[i] = corners[support[i]].dot(directions[i]);
  }
  std::vector<Eigen::Vector3d> kept;
  std::vector<bool> taken(corners.size(), false);
  kept.reserve(max_vertices);
  while (kept.size() < max_vertices) {
    std::size_t worst = 0;
    double shortfall = -1.0;
    for (std::size_t i = 0; i < kThinningDirections; ++i) {
      if (!taken[support[i]] && reach[i] - kept_reach[i] > shortfall) {
        shortfall = reach[i] - kept_reach[i];
        worst = i;
      }
    }
    if (shortfall < 0.0) break;  // every direction's corner is kept
    const Eigen::Vector3d& corner = corners[support[worst]];
    taken[support[worst]] = true;
    kept.push_back(corner);
    for (std::size_t i = 0; i < kThinningDirections; ++i) kept_reach[i] = std::max(kept_reach[i], corner.dot(directions[i]));
  }
  return kept;
}

std::vector<Eigen::Vector3d> collisionHullVertices(const std::string& path, const Eigen::Vector3d& scale) {
  std::vector<Eigen::Vector3d> vertices = readMeshVertices(path);
  for (auto& v : vertices) v = v.cwiseProduct(scale);
  return convexHullVertices(vertices, kMaxCollisionHullVertices, path + " (scaled by its <mesh scale>)");
}

}  // namespace servoloop::sim_common
