#pragma once
// Where servoloop looks for plugin libraries.
//
// The search path, in order (the first library providing a type name wins):
//   1. directories passed in explicitly (tests, command-line flags);
//   2. the entries of SERVOLOOP_PLUGIN_PATH, colon-separated, in order;
//   3. the plugin folder of this servoloop build or installation:
//      <dir of /proc/self/exe>/../lib/servoloop/plugins (plus ../<libdir>/servoloop/plugins
//      when the install libdir is not "lib"), and <dir of libservoloop_controller_manager>
//      /servoloop/plugins for programs installed elsewhere that link servoloop.
//      The build tree mirrors the install tree (bin/, lib/servoloop/plugins/), so
//      the same rule works in build/ and after `cmake --install`.
// Duplicated directories are kept once; directories that do not exist are kept
// (the loader reports them as missing when a type cannot be found).
#include <filesystem>
#include <string_view>
#include <vector>

namespace servoloop::plugin {

// Name of the environment variable adding plugin directories.
inline constexpr const char* kPluginPathEnvVar = "SERVOLOOP_PLUGIN_PATH";

// Splits a colon-separated list, dropping empty entries ("a::b:" -> a, b).
std::vector<std::filesystem::path> splitPluginPath(std::string_view colon_separated);

// The entries of SERVOLOOP_PLUGIN_PATH; empty when it is unset.
std::vector<std::filesystem::path> pluginPathFromEnvironment();

// The plugin folder(s) of this build or installation (rule 3 above).
std::vector<std::filesystem::path> defaultPluginDirectories();

// The whole search path: explicit_dirs, then SERVOLOOP_PLUGIN_PATH, then the
// default folders, without duplicates.
std::vector<std::filesystem::path> pluginSearchPath(
    const std::vector<std::filesystem::path>& explicit_dirs = {});

}  // namespace servoloop::plugin
