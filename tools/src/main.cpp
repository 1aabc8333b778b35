// `servoloop`: one executable, subcommands registered by the files next to
// this one. Exit status 0 on success; on failure one line on stderr and non-zero.
#include <exception>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "command_registry.hpp"

namespace {

// "servoloop control list-types": the subcommands the parser got to, for
// pointing the user at the right --help.
std::string commandPath(const CLI::App& root) {
  std::string path = root.get_name();
  const CLI::App* current = &root;
  while (true) {
    const auto parsed = current->get_subcommands();
    if (parsed.empty()) break;
    current = parsed.front();
    path += " " + current->get_name();
  }
  return path;
}

// A word where a (sub)command belongs that names none: CLI11 would only say
// "A subcommand is required". Returns the one-line error, or "" when the
// words name commands as far as they go.
std::string unknownCommand(const CLI::App& root, int argc, char** argv) {
  const CLI::App* current = &root;
  std::string path = root.get_name();
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word.empty() || word[0] == '-') return "";  // options: CLI11 judges them
    const auto commands = current->get_subcommands([](const CLI::App*) { return true; });
    if (commands.empty()) return "";  // a command's own arguments
    const CLI::App* next = nullptr;
    std::string names;
    for (const CLI::App* command : commands) {
      if (command->check_name(word)) next = command;
      names += (names.empty() ? "" : ", ") + command->get_name();
    }
    if (next == nullptr) return path + ": error: unknown command '" + word + "'; the commands are: " + names;
    current = next;
    path += " " + next->get_name();
  }
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"servoloop: ros_control-style robot control from the command line", "servoloop"};
  app.set_version_flag("--version", SERVOLOOP_VERSION);
  app.require_subcommand(1);
  servoloop::cli::addAllCommands(app);

  if (const std::string unknown = unknownCommand(app, argc, argv); !unknown.empty()) {
    std::cerr << unknown << "\n";
    return static_cast<int>(CLI::ExitCodes::ExtrasError);  // as CLI11 ends for arguments it cannot place
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // --help and --version are "errors" with status 0 that print their text.
    if (error.get_exit_code() == 0) return app.exit(error);
    std::cerr << commandPath(app) << ": error: " << error.what() << " (see '" << commandPath(app)
              << " --help')\n";
    return error.get_exit_code();
  } catch (const servoloop::cli::CliExit& exit) {
    return exit.status;
  } catch (const std::exception& error) {
    std::cerr << commandPath(app) << ": error: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
