// `servoloop plot CSV... -o FILE.png [--columns ...]`: a PNG of recorded
// topics (the CSV files of `servoloop launch --record`), drawn by gnuplot.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command_registry.hpp"
#include "plot_gnuplot.hpp"

namespace servoloop::cli {
namespace {

struct PlotOptions {
  std::vector<std::string> csv_files;
  std::string output;
  std::vector<std::string> columns;
  std::string title;
};

void runPlot(const PlotOptions& options) {
  PlotRequest request;
  for (const std::string& file : options.csv_files) request.csv_files.emplace_back(file);
  request.png = options.output;
  request.columns = options.columns;
  request.title = options.title;
  plotToPng(request);
  std::cout << request.png.string() << "\n";
}

void addPlotCommand(CLI::App& root) {
  auto options = std::make_shared<PlotOptions>();
  CLI::App* plot = root.add_subcommand(
      "plot",
      "Plot recorded topics (CSV files of `servoloop launch --record`) to a PNG: joint position (with the "
      "recorded commands), velocity and effort over simulated time; needs gnuplot (Debian: gnuplot-nox)");
  plot->add_option("csv", options->csv_files, "Recorded CSV files")->required()->check(CLI::ExistingFile);
  plot->add_option("-o,--output", options->output, "PNG file to write")->required()->type_name("FILE.png");
  plot->add_option("--columns", options->columns,
                   "Plot only these columns in one panel (header names, e.g. joint1.position data)")
      ->type_name("NAME");
  plot->add_option("--title", options->title, "Plot title (default: the file names)");
  plot->callback([options] { runPlot(*options); });
}

}  // namespace
}  // namespace servoloop::cli

SERVOLOOP_CLI_COMMANDS(70, servoloop::cli::addPlotCommand)
