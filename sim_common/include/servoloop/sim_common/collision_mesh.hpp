#pragma once
// Collision meshes for every simulation backend. The backends collide with a
// mesh's convex hull, so a mesh comes to them as the vertices of that hull:
// read with assimp (STL, COLLADA, OBJ and the other formats it knows), scaled
// as the URDF's <mesh scale> says, reduced to its hull, and thinned to a
// bounded number of vertices (both engines slow down badly on hulls of
// thousands of vertices). Bullet and MuJoCo get the same points, so they
// collide with the same shape. Non-real-time.
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace servoloop::sim_common {

// The most vertices a collision hull keeps.
inline constexpr std::size_t kMaxCollisionHullVertices = 64;

// Every vertex of the mesh file at `path`, in metres in the file's own axes:
// node transforms and COLLADA's <unit> are applied; COLLADA's <up_axis> is
// not (as rviz and MoveIt load meshes for ROS robots, whose frames are Z-up).
// Throws servoloop::ConfigError naming the file and the fix when it is
// missing, not a mesh, or holds no vertex.
std::vector<Eigen::Vector3d> readMeshVertices(const std::string& path);

// The convex hull of `points`, as its corner vertices (points inside the hull
// or on its faces are dropped, and the corners are input points, unrounded).
// More than `max_vertices` corners are thinned greedily: measured in an even
// spread of directions, the corner of the direction in which the kept corners
// reach least far is kept next, so the kept hull falls short of the full one
// as little as that many corners allow. Throws ConfigError when the points
// span no volume (fewer than four, or all in a plane); `what` names them in
// that message.
std::vector<Eigen::Vector3d> convexHullVertices(const std::vector<Eigen::Vector3d>& points, std::size_t max_vertices,
                                                const std::string& what);

// readMeshVertices, each vertex multiplied by `scale` (per axis; a negative
// factor mirrors), then convexHullVertices with kMaxCollisionHullVertices.
std::vector<Eigen::Vector3d> collisionHullVertices(const std::string& path, const Eigen::Vector3d& scale);

}  // namespace servoloop::sim_common
