#include "stl_mesh.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "servoloop/core/errors.hpp"

namespace servoloop::sim_bullet::detail {
namespace {

constexpr std::size_t kBinaryHeaderBytes = 80;
constexpr std::size_t kBinaryTriangleBytes = 50;  // normal + 3 vertices (12 floats) + attribute word

float readFloatLE(const unsigned char* p) {
  std::uint32_t bits = std::uint32_t(p[0]) | (std::uint32_t(p[1]) << 8) | (std::uint32_t(p[2]) << 16) |
                       (std::uint32_t(p[3]) << 24);
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

std::vector<Eigen::Vector3d> parseBinary(const std::string& bytes, std::size_t triangles) {
  std::vector<Eigen::Vector3d> vertices;
  vertices.reserve(triangles * 3);
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data()) + kBinaryHeaderBytes + 4;
  for (std::size_t t = 0; t < triangles; ++t) {
    const unsigned char* tri = data + t * kBinaryTriangleBytes + 12;  // skip the normal
    for (int v = 0; v < 3; ++v) {
      const unsigned char* p = tri + v * 12;
      vertices.emplace_back(readFloatLE(p), readFloatLE(p + 4), readFloatLE(p + 8));
    }
  }
  return vertices;
}

std::vector<Eigen::Vector3d> parseAscii(const std::string& text, const std::string& path) {
  std::vector<Eigen::Vector3d> vertices;
  std::istringstream in(text);
  std::string word;
  while (in >> word) {
    if (word != "vertex") continue;
    Eigen::Vector3d v;
    if (!(in >> v.x() >> v.y() >> v.z())) {
      throw ConfigError(path + ": ASCII STL 'vertex' without three numbers; the mesh file is corrupt");
    }
    vertices.push_back(v);
  }
  return vertices;
}

}  // namespace

std::vector<Eigen::Vector3d> loadStlVertices(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw ConfigError(path + ": mesh file cannot be opened");
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());

  // A binary file's size is fixed by its triangle count; some binary files
  // start with "solid" too, so the size decides first.
  if (bytes.size() >= kBinaryHeaderBytes + 4) {
    const auto* count_bytes = reinterpret_cast<const unsigned char*>(bytes.data()) + kBinaryHeaderBytes;
    const std::size_t triangles = std::size_t(count_bytes[0]) | (std::size_t(count_bytes[1]) << 8) |
                                  (std::size_t(count_bytes[2]) << 16) | (std::size_t(count_bytes[3]) << 24);
    if (triangles > 0 && bytes.size() == kBinaryHeaderBytes + 4 + triangles * kBinaryTriangleBytes) {
      return parseBinary(bytes, triangles);
    }
  }
  if (bytes.compare(0, 5, "solid") == 0) {
    std::vector<Eigen::Vector3d> vertices = parseAscii(bytes, path);
    if (!vertices.empty()) return vertices;
  }
  throw ConfigError(path + ": not an STL file (neither binary STL of consistent size nor ASCII STL with vertices); "
                    "only STL meshes are supported for collision");
}

}  // namespace servoloop::sim_bullet::detail
