// `servoloop plot`: a PNG of recorded topics (the CSV files of `servoloop
// launch --record`) or of live topics of running nodes (`--topic`, recorded
// for a wall duration or a message count first), drawn by gnuplot.
//
//   servoloop plot js.csv cmd.csv -o run.png
//   servoloop plot --topic /one_DOF_robot/joint_states --duration 5 -o live.png
#include <stdlib.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command_registry.hpp"
#include "node_connection.hpp"
#include "plot_gnuplot.hpp"
#include "plot_live.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::cli {
namespace {

namespace fs = std::filesystem;

struct PlotOptions {
  std::vector<std::string> csv_files;
  std::string output;
  std::vector<std::string> columns;
  std::string title;
  // Live topics.
  std::vector<std::string> topics;
  std::string ns;
  std::optional<double> duration_s;
  std::size_t count = 0;
  std::string save_csv_dir;
};

// A private temporary folder, removed with everything in it when it goes.
class ScratchDir {
 public:
  ScratchDir() {
    std::string pattern = (fs::temp_directory_path() / "servoloop-plot-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw Error("cannot create a temporary folder for the live recordings in " +
                  fs::temp_directory_path().string() + "; give one with --save-csv DIR");
    }
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code error;
    fs::remove_all(path_, error);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string secondsText(double seconds) {
  std::ostringstream text;
  text << seconds;
  return text.str();
}

// Records the live topics into `directory` and returns the files that got
// rows. A topic that carried nothing is left out with a note on stderr; none
// carrying anything is an error.
std::vector<fs::path> recordLiveTopics(const PlotOptions& options, const fs::path& directory) {
  LiveCaptureRequest request;
  request.topics = options.topics;
  request.ns = options.ns;
  request.duration_s = options.duration_s;
  request.count = options.count;
  request.directory = directory;
  std::vector<fs::path> files;
  std::string silent;
  for (const LiveRecording& recording : captureTopics(request)) {
    if (recording.messages > 0) {
      files.push_back(recording.csv);
    } else {
      silent += (silent.empty() ? "" : ", ") + recording.topic;
    }
  }
  if (files.empty()) {
    throw Error("no message arrived on " + silent +
                (options.duration_s ? " within " + secondsText(*options.duration_s) + " s" : std::string()) +
                "; check the topic is published (`servoloop topic hz TOPIC`) or record longer");
  }
  if (!silent.empty()) std::cerr << "servoloop plot: no message on " << silent << "; left out of the plot\n";
  return files;
}

void runPlot(const PlotOptions& options) {
  if (options.topics.empty() && options.csv_files.empty()) {
    throw Error("nothing to plot: give recorded CSV files, or live topics with --topic TOPIC");
  }
  if (!options.topics.empty() && !options.csv_files.empty()) {
    throw Error("give either recorded CSV files or --topic, not both");
  }
  if (options.topics.empty() && (options.duration_s || options.count != 0)) {
    throw Error("--duration and -n/--count apply to live topics only; add --topic TOPIC");
  }

  PlotRequest request;
  request.png = options.output;
  request.columns = options.columns;
  request.title = options.title;
  for (const std::string& file : options.csv_files) request.csv_files.emplace_back(file);

  std::optional<ScratchDir> scratch;
  if (!options.topics.empty()) {
    fs::path directory = options.save_csv_dir;
    if (directory.empty()) directory = scratch.emplace().path();
    request.csv_files = recordLiveTopics(options, directory);
    if (request.title.empty()) {
      for (const std::string& topic : options.topics) {
        request.title += (request.title.empty() ? "" : ", ") + resolveName(options.ns, topic);
      }
    }
  }
  plotToPng(request);
  std::cout << fs::path(options.output).string() << "\n";
}

void addPlotCommand(CLI::App& root) {
  auto options = std::make_shared<PlotOptions>();
  CLI::App* plot = root.add_subcommand(
      "plot",
      "Plot topics to a PNG: recorded ones (CSV files of `servoloop launch --record`) or live ones of a "
      "running node (--topic). Joint states draw as position (with the commands), velocity and effort over "
      "simulated time; needs gnuplot (Debian: gnuplot-nox)");
  plot->add_option("csv", options->csv_files, "Recorded CSV files")->check(CLI::ExistingFile);
  plot->add_option("-o,--output", options->output, "PNG file to write")->required()->type_name("FILE.png");
  plot->add_option("--columns", options->columns,
                   "Plot only these columns in one panel (header names, e.g. joint1.position data)")
      ->type_name("NAME");
  plot->add_option("--title", options->title, "Plot title (default: the file names or topics)");
  plot->add_option("-t,--topic", options->topics,
                   "Record this live topic (repeatable), then plot it; ends after --duration, -n, or Ctrl-C")
      ->type_name("TOPIC");
  plot->add_option("-d,--duration", options->duration_s, "Live topics: record for this many wall seconds")
      ->type_name("SECONDS");
  plot->add_option("-n,--count", options->count,
                   "Live topics: stop after this many messages of the first topic")
      ->type_name("COUNT");
  addNamespaceOption(*plot, options->ns);
  plot->add_option("--save-csv", options->save_csv_dir,
                   "Live topics: keep the recordings as CSV files in this folder (default: discarded)")
      ->type_name("DIR");
  plot->callback([options] { runPlot(*options); });
}

}  // namespace
}  // namespace servoloop::cli

SERVOLOOP_CLI_COMMANDS(70, servoloop::cli::addPlotCommand)
