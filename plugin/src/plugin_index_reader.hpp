#pragma once
// Reading a library file's plugin index (plugin_index.hpp describes the
// records). Internal to the loader; not installed.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "servoloop/plugin/plugin_index.hpp"

namespace servoloop::plugin {

// One record of a library's index.
struct PluginIndexEntry {
  std::uint32_t api_version = 0;
  std::string kind;       // e.g. "controller"
  std::string type_name;  // e.g. "effort_controllers/JointPositionController"
};

// The index of a library file: nullopt when the file is not an ELF shared
// object of this machine's class or has no index section (not a plugin);
// otherwise its records (records that cannot be read are skipped). Reads at
// most the ELF headers and the section; never maps or runs the file.
std::optional<std::vector<PluginIndexEntry>> readPluginIndex(const std::filesystem::path& library);

// The records of an index section's bytes (exposed for tests).
std::vector<PluginIndexEntry> parsePluginIndex(std::string_view section);

}  // namespace servoloop::plugin
