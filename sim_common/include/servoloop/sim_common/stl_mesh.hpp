#pragma once
// The STL reader of every simulation backend (binary and ASCII STL). The
// backends collide with a mesh's convex hull, so the vertices are all they
// need: bullet builds a btConvexHullShape from them, mujoco hands them to
// MuJoCo inline (MuJoCo 2.2 reads only binary STL itself). Non-real-time.
#include <string>
#include <vector>

#include <Eigen/Core>

namespace servoloop::sim_common {

// True when `filename` ends in ".stl", in any letter case: the only mesh
// format the backends collide with.
bool hasStlExtension(const std::string& filename);

// Every triangle corner of the STL file at `path` (duplicates kept, in file
// order), in the file's units. Throws servoloop::ConfigError naming the file
// and the fix when it cannot be read, is not STL, or is a corrupt ASCII STL.
std::vector<Eigen::Vector3d> readStlVertices(const std::string& path);

}  // namespace servoloop::sim_common
