// Finding ROS packages for package:// URIs and $(find pkg): ROS_PACKAGE_PATH
// first (by the <name> in package.xml, not the folder's name), then the
// package.xml files above the description, and one error naming the package
// and where it looked.
#include "servoloop/description/package_path.hpp"

#include <cstdlib>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "servoloop/core/errors.hpp"
#include "temp_dir.hpp"

namespace servoloop {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;
using testing::writeFile;

void writePackage(const fs::path& folder, const std::string& name) {
  writeFile(folder / "package.xml", "<?xml version=\"1.0\"?>\n<package format=\"2\">\n  <name> " + name +
                                        " </name>\n  <version>1.0.0</version>\n</package>\n");
}

// Sets ROS_PACKAGE_PATH for one test and puts back what was there.
class PackagePathEnv {
 public:
  explicit PackagePathEnv(const std::optional<std::string>& value) {
    if (const char* old = std::getenv("ROS_PACKAGE_PATH")) saved_ = old;
    if (value) {
      setenv("ROS_PACKAGE_PATH", value->c_str(), 1);
    } else {
      unsetenv("ROS_PACKAGE_PATH");
    }
  }
  ~PackagePathEnv() {
    if (saved_) {
      setenv("ROS_PACKAGE_PATH", saved_->c_str(), 1);
    } else {
      unsetenv("ROS_PACKAGE_PATH");
    }
  }

 private:
  std::optional<std::string> saved_;
};

TEST(PackagePath, RosPackagePathIsSearchedByPackageXmlName) {
  TempDir dir("servoloop-pkg");
  writePackage(dir.path() / "ws1/src/group/arm_folder", "arm_description");
  writePackage(dir.path() / "ws2/src/arm_description_copy", "arm_description");
  // A folder with the package's name but a different package.xml is not it.
  writePackage(dir.path() / "ws1/src/arm_description", "something_else");
  PackagePathEnv env((dir.path() / "ws1/src").string() + ":" + (dir.path() / "ws2/src").string());
  const fs::path elsewhere = dir.path() / "robot";
  EXPECT_EQ(findPackage("arm_description", elsewhere, "r.urdf"), dir.path() / "ws1/src/group/arm_folder");
  EXPECT_EQ(resolvePackageUri("package://arm_description/meshes/a.stl", elsewhere, "r.urdf"),
            dir.path() / "ws1/src/group/arm_folder/meshes/a.stl");
  EXPECT_EQ(resolvePackageUri("meshes/a.stl", elsewhere, "r.urdf"), fs::path("meshes/a.stl"));
  // A path may wander inside its package, never out of it.
  EXPECT_EQ(resolvePackageUri("package://arm_description/meshes/../urdf/./a.urdf", elsewhere, "r.urdf"),
            dir.path() / "ws1/src/group/arm_folder/urdf/a.urdf");
  for (const char* escape : {"package://arm_description/../../../../etc/passwd",
                             "package://arm_description/meshes/../../arm_description_copy/a.stl"}) {
    try {
      resolvePackageUri(escape, elsewhere, "r.urdf");
      ADD_FAILURE() << escape << " was resolved";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("'" + std::string(escape) + "' leads out of the package folder " +
                                           (dir.path() / "ws1/src/group/arm_folder").string()),
                std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find("r.urdf"), std::string::npos) << e.what();
    }
  }
}

// What a package:// URI names stays inside its package: no ".." package, no
// ".." out of it, no symbolic link out of it; one error naming the URI, the
// package folder and the fix.
TEST(PackagePath, NoPathLeadsOutOfItsPackage) {
  TempDir dir("servoloop-pkg");
  writePackage(dir.path() / "src/arm", "arm");
  writeFile(dir.path() / "secret.txt", "not a mesh");
  writeFile(dir.path() / "src/arm/meshes/a.stl", "solid a\nendsolid a\n");
  const fs::path urdf_dir = dir.path() / "src/arm/urdf";
  fs::create_directories(urdf_dir);
  PackagePathEnv env(std::nullopt);
  const auto errorOf = [&](const std::string& uri) -> std::string {
    try {
      resolvePackageUri(uri, urdf_dir, "arm.urdf");
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "(resolved)";
  };
  // A package named ".." is a folder step, not a package.
  const std::string dotdot = errorOf("package://../../../../etc/passwd");
  EXPECT_NE(dotdot.find("arm.urdf: 'package://../../../../etc/passwd' names no package"), std::string::npos) << dotdot;
  EXPECT_NE(errorOf("package://./meshes/a.stl").find("names no package"), std::string::npos);
  // $(find ..) and $(find a/b) are no package names either.
  EXPECT_THROW(findPackage("..", urdf_dir, "arm.launch"), ConfigError);
  EXPECT_THROW(findPackage("arm/../..", urdf_dir, "arm.launch"), ConfigError);
  // ".." past the package folder.
  const std::string up = errorOf("package://arm/../../secret.txt");
  EXPECT_NE(up.find("'package://arm/../../secret.txt' leads out of the package folder " + (dir.path() / "src/arm").string()),
            std::string::npos)
      << up;
  EXPECT_NE(up.find("remove the '..'"), std::string::npos) << up;
  // A symbolic link inside the package that points out of it.
  std::error_code ec;
  fs::create_directory_symlink(dir.path(), dir.path() / "src/arm/outside", ec);
  ASSERT_FALSE(ec) << ec.message();
  const std::string link = errorOf("package://arm/outside/secret.txt");
  EXPECT_NE(link.find("'package://arm/outside/secret.txt' resolves (through a symbolic link) to " +
                      fs::weakly_canonical(dir.path() / "secret.txt").string()),
            std::string::npos)
      << link;
  EXPECT_NE(link.find(", outside the package folder " + (dir.path() / "src/arm").string()), std::string::npos) << link;
  // What stays inside resolves as before.
  EXPECT_EQ(resolvePackageUri("package://arm/meshes/a.stl", urdf_dir, "arm.urdf"), dir.path() / "src/arm/meshes/a.stl");
  EXPECT_EQ(resolveInsidePackage(dir.path() / "src/arm", "meshes/../meshes/a.stl", "model://arm/meshes/a.stl", "w.sdf"),
            dir.path() / "src/arm/meshes/a.stl");
  EXPECT_THROW(resolveInsidePackage(dir.path() / "src/arm", "/etc/passwd", "model://arm//etc/passwd", "w.sdf"),
               ConfigError);
}

TEST(PackagePath, PackagesAreNotSearchedInsideOtherPackages) {
  TempDir dir("servoloop-pkg");
  writePackage(dir.path() / "src/outer", "outer");
  writePackage(dir.path() / "src/outer/inner", "inner");  // rospack stops at outer's package.xml
  PackagePathEnv env((dir.path() / "src").string());
  EXPECT_THROW(findPackage("inner", dir.path() / "elsewhere", "r.urdf"), ConfigError);
}

TEST(PackagePath, PackageXmlAboveTheDescriptionIsFoundWithoutTheEnvironment) {
  TempDir dir("servoloop-pkg");
  writePackage(dir.path() / "my_robot_description", "my_robot_description");
  writePackage(dir.path() / "my_robot_gazebo", "my_robot_gazebo");
  PackagePathEnv env(std::nullopt);
  const fs::path urdf_dir = dir.path() / "my_robot_description/urdf";
  EXPECT_EQ(findPackage("my_robot_description", urdf_dir, "r.urdf"), dir.path() / "my_robot_description");
  // A sibling package, beside a folder above the description.
  EXPECT_EQ(findPackage("my_robot_gazebo", urdf_dir, "r.urdf"), dir.path() / "my_robot_gazebo");
}

TEST(PackagePath, AFolderNamedLikeThePackageServesDescriptionsWithoutPackageXml) {
  TempDir dir("servoloop-pkg");
  fs::create_directories(dir.path() / "copied/ur_description/urdf");
  PackagePathEnv env(std::nullopt);
  EXPECT_EQ(findPackage("ur_description", dir.path() / "copied/ur_description/urdf", "ur5.urdf"),
            dir.path() / "copied/ur_description");
}

// $(find pkg) for a folder in ROS_PACKAGE_PATH that has no package.xml (a
// description copied without its manifest): the folder serves, as one of that
// name above the file does; one with another package's package.xml does not.
TEST(PackagePath, AFolderNamedLikeThePackageInRosPackagePathServesWithoutPackageXml) {
  TempDir dir("servoloop-pkg");
  fs::create_directories(dir.path() / "ws/src/solo_description/urdf");
  writePackage(dir.path() / "ws/src/other_name", "something_else");
  PackagePathEnv env((dir.path() / "ws/src").string());
  EXPECT_EQ(findPackage("solo_description", dir.path() / "launch", "solo.launch"),
            dir.path() / "ws/src/solo_description");
  EXPECT_THROW(findPackage("other_name", dir.path() / "launch", "solo.launch"), ConfigError);
  PackagePathEnv direct((dir.path() / "ws/src/solo_description/").string());
  EXPECT_EQ(findPackage("solo_description", dir.path() / "launch", "solo.launch"),
            dir.path() / "ws/src/solo_description");
  PackagePathEnv other((dir.path() / "ws/src/other_name").string());
  EXPECT_THROW(findPackage("other_name", dir.path() / "launch", "solo.launch"), ConfigError);
}

TEST(PackagePath, AMissingPackageNamesItAndWhereItLooked) {
  TempDir dir("servoloop-pkg");
  PackagePathEnv env((dir.path() / "ws/src").string());
  try {
    findPackage("no_such_pkg_4711", dir.path() / "robot", "robot.urdf");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("robot.urdf: ROS package 'no_such_pkg_4711' not found"), std::string::npos) << message;
    EXPECT_NE(message.find((dir.path() / "ws/src").string()), std::string::npos) << message;
    EXPECT_NE(message.find("export ROS_PACKAGE_PATH="), std::string::npos) << message;
  }
  EXPECT_THROW(resolvePackageUri("package:///a.stl", dir.path(), "robot.urdf"), ConfigError);
}

}  // namespace
}  // namespace servoloop
