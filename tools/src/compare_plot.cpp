#include "compare_plot.hpp"
#include "plot_gnuplot.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "servoloop/core/errors.hpp"

namespace servoloop::cli {
namespace {

namespace fs = std::filesystem;


// Shortest round-trip form; gnuplot reads NaN as a missing point.
std::string number(double value) {
  if (!std::isfinite(value)) return "NaN";
  char buffer[32];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return error == std::errc() ? std::string(buffer, end) : std::string("NaN");
}

// Data block `name`: time, then every joint's position, then every joint's velocity.
std::string trajectoryBlock(const std::string& name, const JointTrajectory& trajectory) {
  std::string block = name + " << EOD\n";
  for (std::size_t i = 0; i < trajectory.samples(); ++i) {
    block += number(trajectory.time_s[i]);
    for (const auto& column : trajectory.position) block += " " + number(column[i]);
    for (const auto& column : trajectory.velocity) block += " " + number(column[i]);
    block += "\n";
  }
  return block + "EOD\n";
}

// Data block `name`: time, then every compared joint's position difference.
std::string differenceBlock(const std::string& name, const TopicComparison& comparison) {
  std::string block = name + " << EOD\n";
  for (std::size_t i = 0; i < comparison.time_s.size(); ++i) {
    block += number(comparison.time_s[i]);
    for (const auto& column : comparison.position_difference) block += " " + number(column[i]);
    block += "\n";
  }
  return block + "EOD\n";
}

struct Line {
  std::string source;  // data block
  std::size_t column;  // 1-based
  std::string title;
  int colour;          // gnuplot line colour index (one per joint)
  bool dashed;
};

std::string plotCommand(const std::vector<Line>& lines) {
  std::string command = "plot ";
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const Line& line = lines[i];
    command += (i == 0 ? "" : ", \\\n     ") + line.source + " using 1:" + std::to_string(line.column) +
               " with lines linewidth 2 linecolor " + std::to_string(line.colour) + " dashtype " +
               (line.dashed ? "2" : "1") + " title " + gnuplotPlainTitle(line.title);
  }
  return command + "\n";
}

}  // namespace

std::string makeComparisonScript(const ComparisonPlot& plot) {
  if (plot.comparisons.empty() || plot.trajectories_a.size() != plot.comparisons.size() ||
      plot.trajectories_b.size() != plot.comparisons.size()) {
    throw Error("nothing to plot: no compared topic");
  }
  std::ostringstream script;
  script << "set terminal pngcairo size " << plot.width_px << "," << plot.height_px << " enhanced font 'sans,10'\n"
         << "set output " << gnuplotQuoted(plot.png.string()) << "\n"
         << "set grid\nset key outside right top box\n"
         << "set xlabel 'simulated time (s)'\n";

  // Lines per panel; a joint keeps its colour in all three.
  std::vector<Line> positions, velocities, differences;
  int colour = 0;
  const bool several_topics = plot.comparisons.size() > 1;
  for (std::size_t t = 0; t < plot.comparisons.size(); ++t) {
    const JointTrajectory& a = *plot.trajectories_a[t];
    const JointTrajectory& b = *plot.trajectories_b[t];
    const TopicComparison& comparison = *plot.comparisons[t];
    const std::string block_a = "$a" + std::to_string(t);
    const std::string block_b = "$b" + std::to_string(t);
    const std::string block_d = "$d" + std::to_string(t);
    script << trajectoryBlock(block_a, a) << trajectoryBlock(block_b, b) << differenceBlock(block_d, comparison);
    for (std::size_t k = 0; k < comparison.joints.size(); ++k) {
      const std::string& joint = comparison.joints[k].joint;
      const std::string name = several_topics ? comparison.topic + " " + joint : joint;
      const std::size_t ja = a.jointIndex(joint);
      const std::size_t jb = b.jointIndex(joint);
      ++colour;
      positions.push_back({block_a, 2 + ja, name + " " + plot.backend_a, colour, false});
      positions.push_back({block_b, 2 + jb, name + " " + plot.backend_b, colour, true});
      velocities.push_back({block_a, 2 + a.joints.size() + ja, name + " " + plot.backend_a, colour, false});
      velocities.push_back({block_b, 2 + b.joints.size() + jb, name + " " + plot.backend_b, colour, true});
      differences.push_back({block_d, 2 + k, name, colour, false});
    }
  }

  // Fixed margins keep the three time axes aligned whatever the legends' widths.
  script << "set lmargin at screen 0.09\nset rmargin at screen 0.78\n";
  script << "set multiplot layout 3,1 title " << gnuplotPlainTitle(plot.title) << "\n";
  script << "set ylabel 'joint position (rad or m)'\n" << plotCommand(positions);
  script << "set ylabel 'joint velocity (rad/s or m/s)'\n" << plotCommand(velocities);
  script << "set ylabel " << gnuplotQuoted("position difference, " + plot.backend_b + " − " + plot.backend_a) << "\n"
         << plotCommand(differences);
  script << "unset multiplot\nunset output\n";
  return script.str();
}

void plotComparison(const ComparisonPlot& plot) {
  if (plot.png.empty()) throw Error("no PNG file to plot to: give --plot FILE.png");
  runGnuplotScript(makeComparisonScript(plot), plot.png);
}

}  // namespace servoloop::cli
