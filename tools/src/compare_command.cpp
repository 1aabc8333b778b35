// `servoloop compare FILE [--backends A,B] [--duration S] [--pub ...] [--topic T]
// [--plot FILE.png] [--json] [--tolerance X]`: runs one launch file headless on
// two simulation backends in turn (in this process, free-running, no IPC),
// records the joint states of every robot, aligns the two runs by stamp and
// reports per joint the largest position and velocity differences, when they
// occur, and their RMS; --plot overlays both runs. The comparison is
// information: exit 0 once both runs are done, unless --tolerance is given and
// the largest position difference exceeds it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "compare_plot.hpp"
#include "compare_run.hpp"
#include "compare_trajectory.hpp"
#include "servoloop/node/launch_file.hpp"
#include "servoloop/node/run_summary.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::cli {
namespace {

namespace node = servoloop::node;
namespace fs = std::filesystem;
using nlohmann::json;

struct CompareOptions {
  std::string file;
  std::string backends = "bullet,mujoco";
  double duration_s = 10.0;
  std::vector<std::string> publications;
  std::vector<std::string> topics;
  std::string plot;
  bool json = false;
  std::optional<double> tolerance;
  std::vector<std::string> plugin_dirs;
};

// Where the two runs differ most, over every topic and joint.
struct LargestDifference {
  const TopicComparison* topic = nullptr;
  const JointDifference* joint = nullptr;
  double value() const { return joint ? joint->max_position_difference : 0.0; }
};

std::vector<std::string> splitBackends(const std::string& text) {
  std::vector<std::string> names;
  std::stringstream list(text);
  for (std::string name; std::getline(list, name, ',');) {
    name.erase(0, name.find_first_not_of(" \t"));
    name.erase(name.find_last_not_of(" \t") + 1);
    if (!name.empty()) names.push_back(name);
  }
  if (names.size() != 2 || names[0] == names[1]) {
    throw Error("--backends " + text + ": expected two different backends, e.g. --backends bullet,mujoco");
  }
  return names;
}

// printf-style formatting of one number.
std::string formatted(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

std::string controllersLine(const node::RunSummary& summary) {
  std::size_t running = 0;
  std::string others;
  for (const node::RobotSummary& robot : summary.robots) {
    for (const node::ControllerSummary& controller : robot.controllers) {
      if (controller.state == "running") {
        ++running;
        continue;
      }
      others += ", " + robot.robot_namespace + "/" + controller.name + " " + controller.state;
      if (!controller.last_fault.empty()) others += " (" + controller.last_fault + ")";
    }
  }
  return std::to_string(running) + " controller" + (running == 1 ? "" : "s") + " running" + others;
}

LargestDifference largestDifference(const std::vector<TopicComparison>& comparisons) {
  LargestDifference largest;
  for (const TopicComparison& comparison : comparisons) {
    for (const JointDifference& joint : comparison.joints) {
      // !(a <= b) also picks an infinite (diverged) difference.
      if (largest.joint == nullptr || !(joint.max_position_difference <= largest.value())) {
        largest = {&comparison, &joint};
      }
    }
  }
  return largest;
}

std::string textReport(const CompareOptions& options, const BackendRun& a, const BackendRun& b,
                       const std::vector<TopicComparison>& comparisons) {
  std::ostringstream out;
  out << "servoloop compare " << fs::path(options.file).filename().string() << ": " << a.backend << " vs "
      << b.backend << ", " << formatted("%g", options.duration_s) << " s simulated each\n";
  for (const BackendRun* run : {&a, &b}) {
    out << "  " << run->backend << ": " << formatted("%.3f", run->summary.sim_time_s) << " s in "
        << formatted("%.2f", run->summary.wall_time_s) << " s wall; " << controllersLine(run->summary) << "\n";
  }
  for (const TopicComparison& comparison : comparisons) {
    out << comparison.topic << ": " << comparison.samples << " samples from "
        << formatted("%.3f", comparison.start_time_s) << " to " << formatted("%.3f", comparison.end_time_s) << " s"
        << (comparison.max_stamp_offset_s == 0.0
                ? std::string(" (stamps matched exactly)")
                : " (" + b.backend + " interpolated; stamps up to " +
                      formatted("%.3g", comparison.max_stamp_offset_s) + " s apart)")
        << "; differences are " << b.backend << " - " << a.backend << "\n";
    char header[256];
    std::snprintf(header, sizeof header, "  %-16s %-26s %-12s %-28s %-12s %-14s %-14s\n", "joint",
                  "max |d position|", "rms", "max |d velocity|", "rms", ("final " + a.backend).c_str(),
                  ("final " + b.backend).c_str());
    out << header;
    for (const JointDifference& joint : comparison.joints) {
      const std::string velocity_unit = joint.unit + "/s";
      char row[320];
      std::snprintf(row, sizeof row, "  %-16s %-26s %-12s %-28s %-12s %-14.6f %-14.6f\n", joint.joint.c_str(),
                    (formatted("%.3e ", joint.max_position_difference) + joint.unit + " at " +
                     formatted("%.3f s", joint.max_position_time_s))
                        .c_str(),
                    formatted("%.3e", joint.rms_position_difference).c_str(),
                    (formatted("%.3e ", joint.max_velocity_difference) + velocity_unit + " at " +
                     formatted("%.3f s", joint.max_velocity_time_s))
                        .c_str(),
                    formatted("%.3e", joint.rms_velocity_difference).c_str(), joint.final_position_a,
                    joint.final_position_b);
      out << row;
    }
  }
  const LargestDifference largest = largestDifference(comparisons);
  if (largest.joint != nullptr) {
    out << "largest position difference: " << formatted("%.3e", largest.value()) << " " << largest.joint->unit
        << " (" << largest.joint->joint << " at t = " << formatted("%.3f", largest.joint->max_position_time_s)
        << " s, " << b.backend << " - " << a.backend << " = " << formatted("%+.3e", largest.joint->max_position_signed)
        << ")";
    if (options.tolerance) {
      out << (largest.value() <= *options.tolerance ? ", within" : ", exceeds") << " --tolerance "
          << formatted("%g", *options.tolerance);
    }
    out << "\n";
  }
  return out.str();
}

json jsonReport(const CompareOptions& options, const BackendRun& a, const BackendRun& b,
                const std::vector<TopicComparison>& comparisons) {
  json report;
  report["launch_file"] = fs::absolute(options.file).lexically_normal().string();
  report["backends"] = {a.backend, b.backend};
  report["duration"] = options.duration_s;
  report["runs"] = json::array();
  for (const BackendRun* run : {&a, &b}) {
    report["runs"].push_back({{"backend", run->backend}, {"summary", node::toJson(run->summary)}});
  }
  report["topics"] = json::array();
  for (const TopicComparison& comparison : comparisons) {
    json topic = {{"topic", comparison.topic},
                  {"samples", comparison.samples},
                  {"start_time", comparison.start_time_s},
                  {"end_time", comparison.end_time_s},
                  {"max_stamp_offset", comparison.max_stamp_offset_s},
                  {"joints", json::array()}};
    for (const JointDifference& joint : comparison.joints) {
      topic["joints"].push_back({{"name", joint.joint},
                                 {"unit", joint.unit},
                                 {"max_position_difference", joint.max_position_difference},
                                 {"max_position_difference_time", joint.max_position_time_s},
                                 {"position_difference_at_max", joint.max_position_signed},
                                 {"rms_position_difference", joint.rms_position_difference},
                                 {"max_velocity_difference", joint.max_velocity_difference},
                                 {"max_velocity_difference_time", joint.max_velocity_time_s},
                                 {"rms_velocity_difference", joint.rms_velocity_difference},
                                 {"final_position", {{a.backend, joint.final_position_a}, {b.backend, joint.final_position_b}}}});
    }
    report["topics"].push_back(std::move(topic));
  }
  const LargestDifference largest = largestDifference(comparisons);
  report["max_position_difference"] = {{"value", largest.value()},
                                       {"topic", largest.topic ? largest.topic->topic : ""},
                                       {"joint", largest.joint ? largest.joint->joint : ""},
                                       {"time", largest.joint ? largest.joint->max_position_time_s : 0.0}};
  report["tolerance"] = options.tolerance ? json(*options.tolerance) : json(nullptr);
  if (options.tolerance) report["within_tolerance"] = largest.value() <= *options.tolerance;
  return report;
}

void runCompare(const CompareOptions& options) {
  const std::vector<std::string> backends = splitBackends(options.backends);
  if (!(options.duration_s > 0.0)) throw Error("--duration must be more than 0 s");
  std::vector<fs::path> plugin_dirs(options.plugin_dirs.begin(), options.plugin_dirs.end());
  // Both backends are checked before either runs, so a missing one fails at once.
  const std::vector<std::string> available = availableBackends(plugin_dirs);
  for (const std::string& backend : backends) requireBackend(backend, available);

  BackendRunRequest request;
  request.launch = node::loadLaunchFile(options.file);
  for (const std::string& text : options.publications) request.launch.publish.push_back(node::parsePubFlag(text));
  request.duration_s = options.duration_s;
  request.topics = options.topics;
  request.plugin_directories = plugin_dirs;

  std::vector<BackendRun> runs;
  for (const std::string& backend : backends) {
    logger().info("compare: running {} for {} s on '{}'", fs::path(options.file).filename().string(),
                  options.duration_s, backend);
    request.backend = backend;
    runs.push_back(runOnBackend(request));
  }
  const BackendRun& a = runs[0];
  const BackendRun& b = runs[1];

  std::vector<TopicComparison> comparisons;
  for (std::size_t t = 0; t < a.trajectories.size(); ++t) {
    comparisons.push_back(compareTrajectories(a.trajectories[t], b.trajectories[t]));
  }

  if (options.json) {
    std::cout << jsonReport(options, a, b, comparisons).dump() << std::endl;
  } else {
    std::cout << textReport(options, a, b, comparisons) << std::flush;
  }

  if (!options.plot.empty()) {
    ComparisonPlot plot;
    plot.png = fs::absolute(options.plot).lexically_normal();
    plot.title = "servoloop compare " + fs::path(options.file).filename().string() + ": " + a.backend +
                 " (solid) vs " + b.backend + " (dashed)";
    plot.backend_a = a.backend;
    plot.backend_b = b.backend;
    for (std::size_t t = 0; t < comparisons.size(); ++t) {
      plot.trajectories_a.push_back(&a.trajectories[t]);
      plot.trajectories_b.push_back(&b.trajectories[t]);
      plot.comparisons.push_back(&comparisons[t]);
    }
    plotComparison(plot);
    logger().info("plot written to {}", plot.png.string());
  }

  const LargestDifference largest = largestDifference(comparisons);
  if (options.tolerance && !(largest.value() <= *options.tolerance)) {
    throw Error("largest position difference " + formatted("%.3e", largest.value()) + " " + largest.joint->unit +
                " (" + largest.topic->topic + " " + largest.joint->joint + " at t = " +
                formatted("%.3f", largest.joint->max_position_time_s) + " s) exceeds --tolerance " +
                formatted("%g", *options.tolerance));
  }
}

void addCompareCommand(CLI::App& root) {
  auto options = std::make_shared<CompareOptions>();
  CLI::App* compare = root.add_subcommand(
      "compare", "Run one launch file on two simulation backends and report how the joint trajectories differ");
  compare->add_option("file", options->file, "Launch file (YAML), e.g. robots/one_dof/one_dof_w_jnt_ctl.launch.yaml")
      ->required()
      ->check(CLI::ExistingFile);
  compare->add_option("--backends", options->backends, "The two backends, comma-separated (default bullet,mujoco)")
      ->type_name("A,B");
  compare->add_option("--duration", options->duration_s, "Simulated seconds each run lasts (default 10)")
      ->type_name("SECONDS")
      ->check(numberWithin(1e-6, kMaxDurationS, "simulated seconds"));
  compare->add_option("--pub", options->publications,
                      "Publish a message at simulated TIME s (default 0) in both runs: a number is a "
                      "std_msgs/Float64, [a, b] a Float64MultiArray, {field: ...} the type of its topic or TYPE; "
                      "repeatable")
      ->type_name("TOPIC[:TYPE]:=VALUE[@TIME]");
  compare->add_option("--topic", options->topics,
                      "sensor_msgs/JointState topic to compare (repeatable; default: every robot's "
                      "<namespace>/joint_states)")
      ->type_name("TOPIC");
  compare->add_option("--plot", options->plot, "Overlay both runs' trajectories in this PNG (gnuplot)")
      ->type_name("FILE.png");
  compare->add_flag("--json", options->json, "Print the comparison as one JSON object");
  compare->add_option("--tolerance", options->tolerance,
                      "Exit non-zero when the largest position difference exceeds this (rad or m)")
      ->type_name("X")
      ->check(numberWithin(0.0, 1e9, "rad or m"));
  compare->add_option("--plugin-dir", options->plugin_dirs,
                      "Search this directory for plugins first (repeatable); SERVOLOOP_PLUGIN_PATH and the "
                      "installation's plugin folder follow")
      ->type_name("DIR");
  compare->callback([options] { runCompare(*options); });
}

}  // namespace
}  // namespace servoloop::cli

SERVOLOOP_CLI_COMMANDS(15, servoloop::cli::addCompareCommand)
