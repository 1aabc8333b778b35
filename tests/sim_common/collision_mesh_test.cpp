// Collision meshes: STL (binary and ASCII), COLLADA (with its <unit>, in its
// own axes) and OBJ give the same box; <mesh scale> scales and mirrors; a hull
// of thousands of vertices is thinned to a bounded set that still spans it;
// and every error names the file and the fix.
#include "servoloop/sim_common/collision_mesh.hpp"

#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "servoloop/core/errors.hpp"
#include "temp_dir.hpp"

namespace servoloop::sim_common {
namespace {

const std::string kMeshDir = std::string(SERVOLOOP_SOURCE_DIR) + "/tests/assets/meshes/";

std::string readError(const std::string& path) {
  try {
    collisionHullVertices(path, Eigen::Vector3d::Ones());
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected servoloop::ConfigError for " << path;
  return {};
}

// True when `corners` are exactly the 8 corners of the centred box of the
// given half extents (in any order), each within `tolerance`.
::testing::AssertionResult isBox(const std::vector<Eigen::Vector3d>& corners, const Eigen::Vector3d& half,
                                 double tolerance) {
  if (corners.size() != 8) return ::testing::AssertionFailure() << corners.size() << " corners, not 8";
  int seen = 0;
  for (const auto& c : corners) {
    int index = 0;
    for (int axis = 0; axis < 3; ++axis) {
      if (std::abs(std::abs(c[axis]) - half[axis]) > tolerance) {
        return ::testing::AssertionFailure() << "corner (" << c.transpose() << ") is not a corner of the box ("
                                             << half.transpose() << ")";
      }
      index |= (c[axis] > 0 ? 1 : 0) << axis;
    }
    seen |= 1 << index;
  }
  if (seen != 0xff) return ::testing::AssertionFailure() << "a corner appears twice";
  return ::testing::AssertionSuccess();
}

TEST(CollisionMesh, BinaryAndAsciiStlCubesGiveTheCubesCorners) {
  // Binary STL stores 32-bit floats: 0.1f is 0.1 within 1.5e-9.
  EXPECT_TRUE(isBox(collisionHullVertices(kMeshDir + "cube_binary.stl", Eigen::Vector3d::Ones()),
                    Eigen::Vector3d::Constant(0.1), 2e-9));
  EXPECT_TRUE(isBox(collisionHullVertices(kMeshDir + "cube_ascii.stl", Eigen::Vector3d::Ones()),
                    Eigen::Vector3d::Constant(0.1), 2e-9));
}

TEST(CollisionMesh, ColladaUnitsApplyAndItsAxesStayAsWritten) {
  // 20 x 40 x 60 written in centimetres with <up_axis>Z_UP: metres, and the
  // 60 cm side still along z (a Y-up conversion would put it along y).
  EXPECT_TRUE(isBox(collisionHullVertices(kMeshDir + "box_20x40x60cm_zup.dae", Eigen::Vector3d::Ones()),
                    Eigen::Vector3d(0.1, 0.2, 0.3), 1e-7));
}

// assimp keeps coordinates as 32-bit floats: within 2e-8 of the decimal.
constexpr double kFloatTolerance = 2e-8;

TEST(CollisionMesh, ObjGivesTheSameBox) {
  EXPECT_TRUE(isBox(collisionHullVertices(kMeshDir + "box_20x40x60cm.obj", Eigen::Vector3d::Ones()),
                    Eigen::Vector3d(0.1, 0.2, 0.3), kFloatTolerance));
}

TEST(CollisionMesh, ScaleMultipliesEachAxisAndMayMirror) {
  const auto corners = collisionHullVertices(kMeshDir + "box_20x40x60cm.obj", Eigen::Vector3d(2.0, -0.5, 0.001));
  EXPECT_TRUE(isBox(corners, Eigen::Vector3d(0.2, 0.1, 0.0003), 2 * kFloatTolerance));
}

TEST(CollisionMesh, InteriorPointsAreDropped) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 8; ++i) points.emplace_back(i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0);
  points.emplace_back(0.0, 0.0, 0.0);    // inside
  points.emplace_back(0.5, -0.3, 0.9);   // inside
  points.emplace_back(1.0, 0.0, 0.0);    // on a face
  EXPECT_TRUE(isBox(convexHullVertices(points, 64, "points"), Eigen::Vector3d::Ones(), 1e-12));
}

TEST(CollisionMesh, LargeHullsAreThinnedToPointsThatStillSpanThem) {
  // 5,000 points on the unit sphere: every one is a hull corner.
  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  std::vector<Eigen::Vector3d> sphere;
  for (int i = 0; i < 5000; ++i) sphere.push_back(Eigen::Vector3d(normal(random), normal(random), normal(random)).normalized());
  const auto kept = convexHullVertices(sphere, kMaxCollisionHullVertices, "sphere");
  ASSERT_EQ(kept.size(), kMaxCollisionHullVertices);
  for (const auto& p : kept) EXPECT_NEAR(p.norm(), 1.0, 1e-12) << "a kept point is one of the sphere's";
  // In every direction the kept hull reaches nearly as far as the sphere: 64
  // points spread evenly leave gaps of about 0.45 rad (cos 0.23 = 0.97);
  // the bound is looser than that and far above what 64 clustered points give.
  std::vector<Eigen::Vector3d> directions;
  for (int i = 0; i < 2000; ++i) directions.push_back(Eigen::Vector3d(normal(random), normal(random), normal(random)).normalized());
  double worst = 1.0;
  for (const auto& d : directions) {
    double reach = -1.0;
    for (const auto& p : kept) reach = std::max(reach, p.dot(d));
    worst = std::min(worst, reach);
  }
  EXPECT_GT(worst, 0.9);
}

TEST(CollisionMesh, FlatPointSetsHaveNoHull) {
  std::vector<Eigen::Vector3d> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}};
  try {
    convexHullVertices(square, 64, "plate.stl");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("plate.stl spans no volume"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("use a <box>"), std::string::npos) << e.what();
  }
  const auto zero = [] {
    collisionHullVertices(kMeshDir + "box_20x40x60cm.obj", Eigen::Vector3d(1.0, 0.0, 1.0));
  };
  EXPECT_THROW(zero(), ConfigError);
}

TEST(CollisionMesh, MissingFileNamesThePathAndTheFix) {
  const std::string path = kMeshDir + "no_such_mesh.stl";
  const std::string message = readError(path);
  EXPECT_NE(message.find(path + ": cannot read the mesh"), std::string::npos) << message;
  EXPECT_NE(message.find("check the path"), std::string::npos) << message;
}

TEST(CollisionMesh, FilesThatAreNoMeshNameThePathAndTheFix) {
  const servoloop::testing::TempDir dir("servoloop-mesh");
  const std::string path = dir.file("arm.stl");
  servoloop::testing::writeFile(path, "this is not a mesh at all\n");
  const std::string message = readError(path);
  EXPECT_NE(message.find(path + ": "), std::string::npos) << message;
  EXPECT_NE(message.find("export the collision mesh as STL, COLLADA (.dae) or OBJ"), std::string::npos) << message;

  const std::string dae = dir.file("broken.dae");
  servoloop::testing::writeFile(dae, "<COLLADA><library_geometries><geometry>");
  EXPECT_NE(readError(dae).find(dae + ": "), std::string::npos);
}

}  // namespace
}  // namespace servoloop::sim_common
