#pragma once
// Reads the vertices of an STL file (binary or ASCII). MuJoCo 2.2 reads only
// binary STL itself, and collides with a mesh's convex hull anyway, so the
// backend hands MuJoCo the vertices inline and both formats work.
#include <array>
#include <string>
#include <vector>

namespace servoloop::sim_mujoco::detail {

// Every triangle corner of the STL file at `path` (duplicates kept), in the
// file's units. Non-real-time. Throws ConfigError naming the file when it
// cannot be read or is not STL.
std::vector<std::array<double, 3>> readStlVertices(const std::string& path);

}  // namespace servoloop::sim_mujoco::detail
