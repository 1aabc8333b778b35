#pragma once
// Finding a ROS package's folder the way ROS does, for `package://` URIs and
// xacro's `$(find pkg)`. Non-real-time (reads folders).
#include <filesystem>
#include <string>

namespace servoloop {

// The folder of package `name`. Looked for, in order:
//   1. every folder of ROS_PACKAGE_PATH (':'-separated), searched down to a few
//      levels for a package.xml whose <name> is `name`, as rospack does;
//   2. the folders above `near` (normally the file that names the package): one
//      of them, or one of their direct subfolders, with such a package.xml;
//   3. for descriptions copied without their package.xml: a folder above `near`
//      called `name`, or a subfolder called `name` of one of them.
// Throws ConfigError naming `source_name`, the package and where it looked.
std::filesystem::path findPackage(const std::string& name, const std::filesystem::path& near,
                                  const std::string& source_name);

// <package folder>/<relative>, normalised, when it stays inside the package
// folder, both lexically ("a/../../x" is refused) and once symbolic links are
// followed (std::filesystem::weakly_canonical: a link in the package to /etc is
// refused). Otherwise throws ConfigError naming `uri`, the package folder and
// the fix. For every path that is relative to a package: package://, model://
// (a Gazebo model's folder), a mesh path relative to the package's URDF.
std::filesystem::path resolveInsidePackage(const std::filesystem::path& package_folder,
                                           const std::filesystem::path& relative, const std::string& uri,
                                           const std::string& source_name);

// Resolves `package://<pkg>/<rest>` to <package folder>/<rest>; other text is
// returned as it is. Throws as findPackage does, and as resolveInsidePackage
// does for a <rest> that leads out of the package (package://pkg/../../etc/passwd,
// package://../etc/passwd).
std::filesystem::path resolvePackageUri(const std::string& uri, const std::filesystem::path& near,
                                        const std::string& source_name);

}  // namespace servoloop
