#pragma once
// Minimal STL reader (binary and ASCII): the vertices are all the simulation
// needs, since meshes become convex hulls.
#include <string>
#include <vector>

#include <Eigen/Core>

namespace servoloop::sim_bullet::detail {

// Every triangle corner of the STL file at `path` (duplicates kept), in the
// file's units. Throws ConfigError naming the file if it cannot be read or is
// not STL.
std::vector<Eigen::Vector3d> loadStlVertices(const std::string& path);

}  // namespace servoloop::sim_bullet::detail
