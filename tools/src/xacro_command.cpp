// `servoloop xacro FILE [name:=value ...]`: prints the URDF a xacro file
// expands to, as `rosrun xacro xacro` does (servoloop expands xacro itself;
// the other commands take a .xacro file directly).
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command_registry.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/description/xacro.hpp"

namespace servoloop::cli {
namespace {

struct XacroOptions {
  std::string file;
  std::vector<std::string> args;
  std::string output;
};

void runXacro(const XacroOptions& options) {
  XacroArgs args;
  for (const auto& text : options.args) {
    const auto [name, value] = parseXacroArg(text);
    args[name] = value;
  }
  const std::string urdf = expandXacroFile(options.file, args);
  if (options.output.empty()) {
    std::cout << urdf;
    return;
  }
  std::ofstream out(options.output, std::ios::binary);
  if (!(out << urdf)) throw ConfigError("-o " + options.output + ": cannot write the file; check the folder and permissions");
}

void addXacroCommand(CLI::App& root) {
  auto options = std::make_shared<XacroOptions>();
  CLI::App* xacro = root.add_subcommand("xacro", "Expand a xacro file and print the URDF (rosrun xacro xacro)");
  xacro->add_option("file", options->file, "xacro file")->required()->type_name("FILE");
  xacro->add_option("args", options->args, "xacro arguments")->type_name("NAME:=VALUE");
  xacro->add_option("-o,--output", options->output, "Write the URDF to this file instead of printing it")
      ->type_name("FILE");
  xacro->callback([options] { runXacro(*options); });
}

}  // namespace
}  // namespace servoloop::cli

SERVOLOOP_CLI_COMMANDS(72, servoloop::cli::addXacroCommand)
