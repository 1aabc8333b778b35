#include "servoloop/sim_common/stl_mesh.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "servoloop/core/errors.hpp"

namespace servoloop::sim_common {
namespace {

constexpr std::size_t kBinaryHeaderBytes = 80;
constexpr std::size_t kBinaryCountBytes = 4;
constexpr std::size_t kBinaryTriangleBytes = 50;  // normal, 3 corners (12 floats), attribute word
constexpr std::size_t kBinaryNormalBytes = 12;
constexpr std::size_t kBinaryCornerBytes = 12;

// STL stores little-endian values whatever the machine's byte order.
std::uint32_t readUint32LE(const unsigned char* p) {
  return std::uint32_t(p[0]) | (std::uint32_t(p[1]) << 8) | (std::uint32_t(p[2]) << 16) |
         (std::uint32_t(p[3]) << 24);
}

float readFloatLE(const unsigned char* p) {
  const std::uint32_t bits = readUint32LE(p);
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

std::vector<Eigen::Vector3d> parseBinary(const std::string& bytes, std::size_t triangles) {
  std::vector<Eigen::Vector3d> vertices;
  vertices.reserve(triangles * 3);
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data()) + kBinaryHeaderBytes + kBinaryCountBytes;
  for (std::size_t t = 0; t < triangles; ++t) {
    const unsigned char* corner = data + t * kBinaryTriangleBytes + kBinaryNormalBytes;
    for (int c = 0; c < 3; ++c, corner += kBinaryCornerBytes) {
      vertices.emplace_back(readFloatLE(corner), readFloatLE(corner + 4), readFloatLE(corner + 8));
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
      throw ConfigError(path + ": ASCII STL 'vertex' without three numbers; the mesh file is corrupt, "
                               "export the collision mesh as STL again");
    }
    vertices.push_back(v);
  }
  return vertices;
}

}  // namespace

bool hasStlExtension(const std::string& filename) {
  if (filename.size() < 4) return false;
  std::string extension = filename.substr(filename.size() - 4);
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".stl";
}

std::vector<Eigen::Vector3d> readStlVertices(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw ConfigError(path + ": cannot read the STL mesh; check the path and permissions");
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());

  // A binary file's size is fixed by its triangle count; an ASCII file starts
  // with "solid" (some binary exporters write "solid" too, hence the size test first).
  if (bytes.size() >= kBinaryHeaderBytes + kBinaryCountBytes) {
    const std::size_t triangles =
        readUint32LE(reinterpret_cast<const unsigned char*>(bytes.data()) + kBinaryHeaderBytes);
    if (triangles > 0 &&
        bytes.size() == kBinaryHeaderBytes + kBinaryCountBytes + triangles * kBinaryTriangleBytes) {
      return parseBinary(bytes, triangles);
    }
  }
  if (bytes.rfind("solid", 0) == 0) {
    std::vector<Eigen::Vector3d> vertices = parseAscii(bytes, path);
    if (!vertices.empty()) return vertices;
  }
  throw ConfigError(path + ": not an STL mesh (neither binary STL of consistent size nor ASCII STL with "
                           "'vertex' lines); export the collision mesh as STL");
}

}  // namespace servoloop::sim_common
