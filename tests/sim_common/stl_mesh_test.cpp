// The STL reader both backends collide with: the test cube in binary and in
// ASCII STL gives the same 36 corners (12 triangles), and every error names
// the file and the fix.
#include "servoloop/sim_common/stl_mesh.hpp"

#include <string>

#include <gtest/gtest.h>

#include "servoloop/core/errors.hpp"
#include "temp_dir.hpp"

namespace servoloop::sim_common {
namespace {

const std::string kMeshDir = std::string(SERVOLOOP_SOURCE_DIR) + "/tests/assets/meshes/";

// The message of the ConfigError that reading `path` throws ("" if none).
std::string readError(const std::string& path) {
  try {
    readStlVertices(path);
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected servoloop::ConfigError for " << path;
  return {};
}

TEST(StlMesh, BinaryAndAsciiCubesGiveTheSameCornersInFileOrder) {
  const auto binary = readStlVertices(kMeshDir + "cube_binary.stl");
  const auto ascii = readStlVertices(kMeshDir + "cube_ascii.stl");
  ASSERT_EQ(binary.size(), 36u);
  ASSERT_EQ(ascii.size(), 36u);
  // The first triangle as written in cube_ascii.stl.
  EXPECT_EQ(ascii[0], Eigen::Vector3d(-0.1, -0.1, -0.1));
  EXPECT_EQ(ascii[1], Eigen::Vector3d(-0.1, -0.1, 0.1));
  EXPECT_EQ(ascii[2], Eigen::Vector3d(-0.1, 0.1, 0.1));
  for (std::size_t i = 0; i < ascii.size(); ++i) {
    SCOPED_TRACE("corner " + std::to_string(i));
    // Binary STL stores 32-bit floats: 0.1f is 0.1 within 1.5e-9.
    EXPECT_NEAR((binary[i] - ascii[i]).cwiseAbs().maxCoeff(), 0.0, 2e-9);
    EXPECT_EQ(Eigen::Vector3d(ascii[i].cwiseAbs()), Eigen::Vector3d::Constant(0.1)) << "a corner of the 0.2 m cube";
  }
}

TEST(StlMesh, RecognisesTheExtensionInAnyCase) {
  EXPECT_TRUE(hasStlExtension("meshes/arm.stl"));
  EXPECT_TRUE(hasStlExtension("ARM.STL"));
  EXPECT_TRUE(hasStlExtension(".Stl"));
  EXPECT_FALSE(hasStlExtension("cube.dae"));
  EXPECT_FALSE(hasStlExtension("stl"));
  EXPECT_FALSE(hasStlExtension("cube.stl.obj"));
}

TEST(StlMesh, MissingFileNamesThePathAndTheFix) {
  const std::string path = kMeshDir + "no_such_mesh.stl";
  const std::string message = readError(path);
  EXPECT_NE(message.find(path + ": cannot read the STL mesh"), std::string::npos) << message;
  EXPECT_NE(message.find("check the path and permissions"), std::string::npos) << message;
}

TEST(StlMesh, NonStlFileNamesThePathAndTheFix) {
  const servoloop::testing::TempDir dir("servoloop-stl");
  const std::string path = dir.file("cube.stl");
  // Long enough for a binary header, but of the wrong size for its count.
  servoloop::testing::writeFile(path, "COLLADA" + std::string(120, ' '));
  const std::string message = readError(path);
  EXPECT_NE(message.find(path + ": not an STL mesh"), std::string::npos) << message;
  EXPECT_NE(message.find("export the collision mesh as STL"), std::string::npos) << message;

  // ASCII without a single vertex is no mesh either.
  servoloop::testing::writeFile(path, "solid empty\nendsolid empty\n");
  EXPECT_NE(readError(path).find(path + ": not an STL mesh"), std::string::npos);
}

TEST(StlMesh, CorruptAsciiVertexNamesThePathAndTheFix) {
  const servoloop::testing::TempDir dir("servoloop-stl");
  const std::string path = dir.file("broken.stl");
  servoloop::testing::writeFile(path, "solid broken\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n"
                                      "   vertex 1 zero 0\n   vertex 0 1 0\n  endloop\n endfacet\nendsolid\n");
  const std::string message = readError(path);
  EXPECT_NE(message.find(path + ": ASCII STL 'vertex' without three numbers"), std::string::npos) << message;
  EXPECT_NE(message.find("export the collision mesh as STL again"), std::string::npos) << message;
}

}  // namespace
}  // namespace servoloop::sim_common
