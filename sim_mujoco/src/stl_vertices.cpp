#include "stl_vertices.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "servoloop/core/errors.hpp"

namespace servoloop::sim_mujoco::detail {
namespace {

constexpr std::size_t kBinaryHeaderBytes = 80;
constexpr std::size_t kBinaryTriangleBytes = 50;  // normal, 3 corners (12 floats), attribute word

std::vector<std::array<double, 3>> parseBinary(const std::string& bytes) {
  std::uint32_t triangles = 0;
  std::memcpy(&triangles, bytes.data() + kBinaryHeaderBytes, sizeof(triangles));
  std::vector<std::array<double, 3>> vertices;
  vertices.reserve(std::size_t{3} * triangles);
  for (std::uint32_t t = 0; t < triangles; ++t) {
    const char* corner = bytes.data() + kBinaryHeaderBytes + 4 + t * kBinaryTriangleBytes + 12;
    for (int c = 0; c < 3; ++c, corner += 12) {
      float xyz[3];
      std::memcpy(xyz, corner, sizeof(xyz));
      vertices.push_back({xyz[0], xyz[1], xyz[2]});
    }
  }
  return vertices;
}

std::vector<std::array<double, 3>> parseAscii(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::array<double, 3>> vertices;
  std::string word;
  while (in >> word) {
    if (word != "vertex") continue;
    std::array<double, 3> v{};
    if (!(in >> v[0] >> v[1] >> v[2])) break;
    vertices.push_back(v);
  }
  return vertices;
}

}  // namespace

std::vector<std::array<double, 3>> readStlVertices(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw ConfigError(path + ": cannot read the STL mesh; check the path and permissions");
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());

  // A binary file's size is fixed by its triangle count; an ASCII file starts
  // with "solid" (some binary exporters write "solid" too, hence the size test first).
  if (bytes.size() >= kBinaryHeaderBytes + 4) {
    std::uint32_t triangles = 0;
    std::memcpy(&triangles, bytes.data() + kBinaryHeaderBytes, sizeof(triangles));
    if (triangles > 0 && bytes.size() == kBinaryHeaderBytes + 4 + std::size_t{triangles} * kBinaryTriangleBytes) {
      return parseBinary(bytes);
    }
  }
  if (bytes.rfind("solid", 0) == 0) {
    std::vector<std::array<double, 3>> vertices = parseAscii(bytes);
    if (!vertices.empty()) return vertices;
  }
  throw ConfigError(path + ": not an STL mesh (neither binary STL nor ASCII STL with 'vertex' lines); "
                    "export the collision mesh as STL");
}

}  // namespace servoloop::sim_mujoco::detail
