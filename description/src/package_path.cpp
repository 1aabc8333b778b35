#include "servoloop/description/package_path.hpp"

#include <cstdlib>
#include <sstream>
#include <vector>

#include <tinyxml2.h>

#include "servoloop/core/errors.hpp"

namespace servoloop {
namespace fs = std::filesystem;
namespace {

// rospack stops at a package and does not descend further; a bound on depth
// keeps a ROS_PACKAGE_PATH entry such as $HOME from crawling a whole disk.
constexpr int kMaxCrawlDepth = 5;

// The <name> in `folder`/package.xml, or "" when there is none.
std::string packageXmlName(const fs::path& folder) {
  std::error_code ec;
  const fs::path manifest = folder / "package.xml";
  if (!fs::is_regular_file(manifest, ec)) return "";
  tinyxml2::XMLDocument document;
  if (document.LoadFile(manifest.c_str()) != tinyxml2::XML_SUCCESS) return "";
  const tinyxml2::XMLElement* root = document.RootElement();
  const tinyxml2::XMLElement* name = root ? root->FirstChildElement("name") : nullptr;
  if (name == nullptr || name->GetText() == nullptr) return "";
  std::string text = name->GetText();
  const auto first = text.find_first_not_of(" \t\r\n");
  const auto last = text.find_last_not_of(" \t\r\n");
  return first == std::string::npos ? "" : text.substr(first, last - first + 1);
}

bool crawl(const fs::path& folder, const std::string& name, int depth, fs::path& found) {
  const std::string here = packageXmlName(folder);
  if (!here.empty()) {
    if (here != name) return false;
    found = folder;
    return true;
  }
  if (depth >= kMaxCrawlDepth) return false;
  std::error_code ec;
  for (fs::directory_iterator it(folder, fs::directory_options::skip_permission_denied, ec), end;
       !ec && it != end; it.increment(ec)) {
    const auto& entry = *it;
    std::error_code type_ec;
    if (!entry.is_directory(type_ec) || entry.is_symlink(type_ec)) continue;
    const std::string base = entry.path().filename().string();
    if (base.empty() || base[0] == '.') continue;
    if (crawl(entry.path(), name, depth + 1, found)) return true;
  }
  return false;
}

std::vector<fs::path> rosPackagePath() {
  std::vector<fs::path> roots;
  if (const char* env = std::getenv("ROS_PACKAGE_PATH")) {
    std::stringstream ss(env);
    std::string dir;
    while (std::getline(ss, dir, ':')) {
      if (!dir.empty()) roots.emplace_back(dir);
    }
  }
  return roots;
}

std::vector<fs::path> foldersAbove(const fs::path& near) {
  std::vector<fs::path> folders;
  std::error_code ec;
  fs::path start = fs::absolute(near, ec);
  if (!fs::is_directory(start, ec)) start = start.parent_path();
  for (fs::path p = start.lexically_normal(); !p.empty(); p = p.parent_path()) {
    folders.push_back(p);
    if (p == p.parent_path()) break;
  }
  return folders;
}

}  // namespace

fs::path findPackage(const std::string& name, const fs::path& near, const std::string& source_name) {
  if (name.empty()) throw ConfigError(source_name + ": an empty ROS package name; write package://<package>/<path>");
  // ".." or "a/../b" would be a folder above or beside the file, not a package
  // (and package://../../etc/passwd a file anywhere on the disk).
  if (name == "." || name == ".." || name.find_first_of("/\\") != std::string::npos) {
    throw ConfigError(source_name + ": '" + name + "' is not a ROS package name (a package is named by letters, " +
                      "digits, '_' and '-', without '/' or '..'); write package://<package>/<path inside it>");
  }
  fs::path found;
  const std::vector<fs::path> roots = rosPackagePath();
  for (const auto& root : roots) {
    if (crawl(root, name, 0, found)) return found;
  }
  const std::vector<fs::path> above = foldersAbove(near);
  std::error_code ec;
  for (const auto& folder : above) {
    if (packageXmlName(folder) == name) return folder;
    for (fs::directory_iterator it(folder, fs::directory_options::skip_permission_denied, ec), end;
         !ec && it != end; it.increment(ec)) {
      std::error_code type_ec;
      if (it->is_directory(type_ec) && packageXmlName(it->path()) == name) return it->path();
    }
  }
  // Without a package.xml anywhere, a folder of the package's name serves: a
  // ROS_PACKAGE_PATH entry (or the folder of that name in one), or one above
  // the file (descriptions copied out of their workspace).
  for (fs::path root : roots) {
    if (!root.has_filename()) root = root.parent_path();  // "/ws/src/pkg/"
    if (root.filename() == name && fs::is_directory(root, ec) && packageXmlName(root).empty()) return root;
    if (fs::is_directory(root / name, ec) && packageXmlName(root / name).empty()) return root / name;
  }
  for (const auto& folder : above) {
    if (folder.filename() == name) return folder;
    if (fs::is_directory(folder / name, ec)) return folder / name;
  }
  std::string looked = "ROS_PACKAGE_PATH ";
  if (roots.empty()) {
    looked += "(not set)";
  } else {
    for (std::size_t i = 0; i < roots.size(); ++i) looked += (i ? ":" : "") + roots[i].string();
  }
  looked += ", then package.xml files and folders named '" + name + "' above " +
            (above.empty() ? near.string() : above.front().string());
  throw ConfigError(source_name + ": ROS package '" + name + "' not found (looked in " + looked +
                    "); add the folder that holds it to ROS_PACKAGE_PATH, e.g. export ROS_PACKAGE_PATH=/path/to/"
                    "src:$ROS_PACKAGE_PATH (a package is found by the <name> of its package.xml, or as a folder '" +
                    name + "' without one)");
}

fs::path resolveInsidePackage(const fs::path& package_folder, const fs::path& relative, const std::string& uri,
                              const std::string& source_name) {
  const auto refuse = [&](const std::string& why) -> void {
    throw ConfigError(source_name + ": '" + uri + "' " + why + " the package folder " + package_folder.string() +
                      "; a package path names a file inside its package: remove the '..' (or the link out of the "
                      "package), or copy the file into the package");
  };
  const fs::path inside = relative.lexically_normal();
  if (inside.is_absolute() || inside.has_root_name() || (!inside.empty() && *inside.begin() == "..")) {
    refuse("leads out of");
  }
  const fs::path joined = (package_folder / inside).lexically_normal();
  // Lexically inside, but a symbolic link on the way may still lead out.
  std::error_code ec;
  const fs::path real_folder = fs::weakly_canonical(package_folder, ec);
  std::error_code ec_joined;
  const fs::path real_joined = fs::weakly_canonical(joined, ec_joined);
  if (!ec && !ec_joined) {
    const fs::path rest = real_joined.lexically_relative(real_folder);
    if (rest.empty() || *rest.begin() == "..") refuse("resolves (through a symbolic link) to " + real_joined.string() + ", outside");
  }
  return joined;
}

fs::path resolvePackageUri(const std::string& uri, const fs::path& near, const std::string& source_name) {
  const std::string prefix = "package://";
  if (uri.rfind(prefix, 0) != 0) return uri;
  const std::string rest = uri.substr(prefix.size());
  const auto slash = rest.find('/');
  const std::string package = rest.substr(0, slash);
  if (package == "." || package == "..") {
    throw ConfigError(source_name + ": '" + uri + "' names no package ('" + package +
                      "' is a folder step, not a ROS package name) and would lead out of any package folder; "
                      "write package://<package>/<path inside it>");
  }
  const fs::path folder = findPackage(package, near, source_name);
  if (slash == std::string::npos) return folder;
  return resolveInsidePackage(folder, fs::path(rest.substr(slash + 1)), uri, source_name);
}

}  // namespace servoloop
