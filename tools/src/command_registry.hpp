#pragma once
// How subcommand groups join the `servoloop` command line. A group's .cpp file
// defines a function adding its subcommands to the root app and registers it:
//
//   namespace { void addTopicCommands(CLI::App& root) { ... } }
//   SERVOLOOP_CLI_COMMANDS(30, addTopicCommands)
//
// Commands do their work in a CLI11 callback. On failure they throw
// servoloop::Error (or any std::exception) whose message is the one line the
// user sees; CliExit ends with a given status and no message.
#include <string>

#include <CLI/CLI.hpp>

namespace servoloop::cli {

using CommandAdder = void (*)(CLI::App& root);

// Static registration; `order` sorts the groups in --help (launch 10,
// spawner 20, control 30, topic 40, param 50, ...; ties by registration).
struct CommandRegistration {
  CommandRegistration(int order, CommandAdder add);
};

// Calls every registered adder, in order.
void addAllCommands(CLI::App& root);

// The subcommand `name` of `parent`, created on first use: several files may
// add subcommands to one group ("control list-types" here, "control load" in
// another file). Groups require one of their subcommands.
CLI::App& commandGroup(CLI::App& parent, const std::string& name, const std::string& description);

// A check for a number option: finite (no nan or inf) and within [low, high],
// with a message that prints the bounds as written ("--duration: 1e300 is
// outside 0 to 1e+09 (seconds)"), not as CLI11 prints DBL_MAX.
CLI::Validator numberWithin(double low, double high, const std::string& unit);

// The longest simulated run a command accepts, in seconds (about 31 years):
// its steps stay exact integers in a double at the smallest time step.
inline constexpr double kMaxDurationS = 1e9;

// Thrown by a command to exit with `status` without printing anything more.
struct CliExit {
  int status;
};

}  // namespace servoloop::cli

#define SERVOLOOP_CLI_CONCAT_INNER(a, b) a##b
#define SERVOLOOP_CLI_CONCAT(a, b) SERVOLOOP_CLI_CONCAT_INNER(a, b)
#define SERVOLOOP_CLI_COMMANDS(order, adder)                                               \
  namespace {                                                                              \
  const ::servoloop::cli::CommandRegistration SERVOLOOP_CLI_CONCAT(servoloop_cli_commands_, \
                                                                   __COUNTER__){order, adder}; \
  }
