// `servoloop control ...`: the controller manager's commands. This file holds
// the ones that need no running node (list-types); commands that talk to a
// node add themselves to the same group from their own files.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "servoloop/plugin/plugin_loader.hpp"
#include "servoloop/plugin/plugin_path.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::cli {
namespace {

namespace fs = std::filesystem;

struct ListTypesOptions {
  bool json = false;
  std::string kind;
  std::vector<std::string> plugin_dirs;
};

void printTable(const std::vector<servoloop::plugin::PluginTypeInfo>& types) {
  if (types.empty()) return;
  std::size_t type_width = 4;
  std::size_t kind_width = 4;
  for (const auto& type : types) {
    type_width = std::max(type_width, type.type.size());
    kind_width = std::max(kind_width, type.kind.size());
  }
  auto row = [&](const std::string& type, const std::string& kind, const std::string& library) {
    std::cout << type << std::string(type_width - type.size() + 2, ' ') << kind
              << std::string(kind_width - kind.size() + 2, ' ') << library << "\n";
  };
  row("TYPE", "KIND", "LIBRARY");
  for (const auto& type : types) row(type.type, type.kind, type.library.string());
}

void printJson(const std::vector<servoloop::plugin::PluginTypeInfo>& types) {
  nlohmann::json array = nlohmann::json::array();
  for (const auto& type : types) {
    array.push_back({{"type", type.type}, {"kind", type.kind}, {"library", type.library.string()}});
  }
  std::cout << array.dump(2) << "\n";
}

// Libraries that fail to load are reported by the loader as warnings on
// stderr; they do not make the listing fail.
void runListTypes(const ListTypesOptions& options) {
  std::vector<fs::path> explicit_dirs;
  for (const auto& dir : options.plugin_dirs) {
    if (!fs::is_directory(dir)) {
      throw Error("--plugin-dir '" + dir + "' is not a directory");
    }
    explicit_dirs.emplace_back(dir);
  }
  const servoloop::plugin::PluginLoader loader(servoloop::plugin::pluginSearchPath(explicit_dirs));
  const auto types = loader.listTypes(options.kind);
  if (options.json) {
    printJson(types);
  } else {
    printTable(types);
  }
}

void addControlCommands(CLI::App& root) {
  CLI::App& control = commandGroup(
      root, "control", "Controller manager: list, load, start, stop and switch controllers");

  auto options = std::make_shared<ListTypesOptions>();
  CLI::App* list_types = control.add_subcommand(
      "list-types",
      "List every plugin type (controllers, backends) on the plugin path; needs no running node");
  list_types->add_flag("--json", options->json, "Print a JSON array of {type, kind, library}");
  list_types->add_option("--kind", options->kind,
                         "Only this kind of plugin, e.g. controller or robot_hw");
  list_types->add_option("--plugin-dir", options->plugin_dirs,
                         "Search this directory first (repeatable); SERVOLOOP_PLUGIN_PATH and "
                         "the installation's plugin folder are searched after it")
      ->type_name("DIR");
  list_types->callback([options] { runListTypes(*options); });
}

}  // namespace
}  // namespace servoloop::cli

SERVOLOOP_CLI_COMMANDS(30, servoloop::cli::addControlCommands)
