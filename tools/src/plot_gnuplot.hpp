#pragma once
// PNG plots of recorded topics, drawn by gnuplot (Debian package gnuplot-nox,
// pngcairo terminal) fed a generated script through a pipe.
//
// With a sensor_msgs/JointState recording among the files: three panels over
// simulated time — joint position (rad), velocity (rad/s) and effort (N·m) —
// with every std_msgs/Float64 recording (a position command) drawn as a step
// line over the positions. Otherwise, or with explicit columns: one panel of
// the chosen columns of every file over time.
#include <filesystem>
#include <string>
#include <vector>

namespace servoloop::cli {

struct PlotRequest {
  std::vector<std::filesystem::path> csv_files;
  std::filesystem::path png;
  // Only these columns (header names such as joint1.position or data); empty:
  // the layout described above.
  std::vector<std::string> columns;
  std::string title;  // empty: made from the file names
  int width_px = 1200;
  int height_px = 900;
};

// The gnuplot script for a request (reads the CSV headers). Throws
// servoloop::Error naming the file or column at fault.
std::string makeGnuplotScript(const PlotRequest& request);

// Runs gnuplot on the script and checks the PNG exists. Throws servoloop::Error
// when gnuplot is not installed (naming the package to install) or fails
// (with its first error line).
void plotToPng(const PlotRequest& request);

// A gnuplot single-quoted string ('' stands for a quote inside it).
std::string gnuplotQuoted(const std::string& text);
// A title gnuplot prints as it is: quoted, with enhanced-text markup (_ ^ @ & { })
// switched off.
std::string gnuplotPlainTitle(const std::string& text);

// Runs gnuplot on any script that writes png (the script sets the terminal
// and output), with the same checks and errors as plotToPng.
void runGnuplotScript(const std::string& script, const std::filesystem::path& png);

}  // namespace servoloop::cli
