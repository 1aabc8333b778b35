#include "command_registry.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
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

CLI::Validator numberWithin(double low, double high, const std::string& unit) {
  const auto shortest = [](double v) {
    std::ostringstream text;
    text << v;
    return text.str();
  };
  const std::string range = shortest(low) + " to " + shortest(high) + " (" + unit + ")";
  return CLI::Validator(
      [low, high, range](std::string& input) -> std::string {
        double value = 0.0;
        std::size_t used = 0;
        try {
          value = std::stod(input, &used);
        } catch (const std::exception&) {
          return "'" + input + "' is not a number; give " + range;
        }
        if (used != input.size()) return "'" + input + "' is not a number; give " + range;
        if (!std::isfinite(value) || value < low || value > high) return input + " is outside " + range;
        return "";
      },
      "NUMBER in " + range);
}

}  // namespace servoloop::cli
