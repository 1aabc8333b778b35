#include "servoloop/plugin/plugin_path.hpp"

#include <algorithm>
#include <cstdlib>
#include <mutex>
#include <set>
#include <string>
#include <system_error>

#include "servoloop/core/executable_path.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::plugin {
namespace fs = std::filesystem;

namespace {

// Install libdir relative to the prefix (e.g. "lib" or "lib/x86_64-linux-gnu"),
// set by the build; the build tree always uses "lib".
#ifndef SERVOLOOP_INSTALL_LIBDIR
#define SERVOLOOP_INSTALL_LIBDIR "lib"
#endif

fs::path pluginsUnder(const fs::path& lib_dir) { return lib_dir / "servoloop" / "plugins"; }

// Relative entries are taken relative to the current directory, once, so that
// "plugins" and "./plugins" count as one directory.
void appendUnique(std::vector<fs::path>& dirs, const fs::path& dir) {
  std::error_code error;
  fs::path normal = fs::absolute(dir, error).lexically_normal();
  if (error) normal = dir.lexically_normal();
  if (!normal.has_filename() && normal.has_parent_path()) normal = normal.parent_path();
  if (std::find(dirs.begin(), dirs.end(), normal) == dirs.end()) dirs.push_back(normal);
}

// Address inside this library, for loadedObjectDirectory.
void anchor() {}

}  // namespace

std::vector<fs::path> splitPluginPath(std::string_view colon_separated) {
  std::vector<fs::path> dirs;
  std::size_t start = 0;
  while (start <= colon_separated.size()) {
    const std::size_t end = std::min(colon_separated.find(':', start), colon_separated.size());
    if (end > start) dirs.emplace_back(std::string(colon_separated.substr(start, end - start)));
    start = end + 1;
  }
  return dirs;
}

std::vector<fs::path> pluginPathFromEnvironment() {
  const char* value = std::getenv(kPluginPathEnvVar);
  return value ? splitPluginPath(value) : std::vector<fs::path>{};
}

std::vector<fs::path> defaultPluginDirectories() {
  std::vector<fs::path> dirs;
  std::error_code error;
  const fs::path bin = executableDirectory(error);
  if (!error) {
    const fs::path prefix = bin.parent_path();
    appendUnique(dirs, pluginsUnder(prefix / "lib"));
    appendUnique(dirs, pluginsUnder(prefix / SERVOLOOP_INSTALL_LIBDIR));
  }
  // A program outside the servoloop tree that links this library still finds
  // the plugins installed next to it.
  const fs::path library_dir = loadedObjectDirectory(reinterpret_cast<const void*>(&anchor), error);
  if (!error) appendUnique(dirs, pluginsUnder(library_dir));
  return dirs;
}

std::vector<fs::path> pluginSearchPath(const std::vector<fs::path>& explicit_dirs) {
  std::vector<fs::path> dirs;
  for (const auto& dir : explicit_dirs) appendUnique(dirs, dir);
  for (const auto& dir : pluginPathFromEnvironment()) appendUnique(dirs, dir);
  // A folder the user named that is not there is most likely a typo; the
  // default folders may legitimately be missing.
  static std::mutex warned_mutex;
  static std::set<fs::path> warned;
  for (const auto& dir : dirs) {
    std::error_code error;
    if (fs::is_directory(dir, error)) continue;
    std::lock_guard lock(warned_mutex);
    if (!warned.insert(dir).second) continue;
    logger().warn("plugin folder '{}' (from --plugin-dir or {}) {}; check the path", dir.string(), kPluginPathEnvVar,
                  fs::exists(dir, error) ? "is not a folder" : "does not exist");
  }
  for (const auto& dir : defaultPluginDirectories()) appendUnique(dirs, dir);
  return dirs;
}

}  // namespace servoloop::plugin
