#include "command_registry.hpp"

#include <algorithm>
#include <utility>
#include <vector>

namespace servoloop::cli {
namespace {

std::vector<std::pair<int, CommandAdder>>& registrations() {
  static std::vector<std::pair<int, CommandAdder>> all;
  return all;
}

}  // namespace

CommandRegistration::CommandRegistration(int order, CommandAdder add) {
  registrations().emplace_back(order, add);
}

void addAllCommands(CLI::App& root) {
  auto sorted = registrations();
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [order, add] : sorted) add(root);
}

CLI::App& commandGroup(CLI::App& parent, const std::string& name, const std::string& description) {
  for (CLI::App* existing : parent.get_subcommands([](CLI::App*) { return true; })) {
    if (existing->get_name() == name) return *existing;
  }
  CLI::App* group = parent.add_subcommand(name, description);
  group->require_subcommand(1);
  return *group;
}

}  // namespace servoloop::cli
