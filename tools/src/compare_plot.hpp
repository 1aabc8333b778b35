#pragma once
// The PNG of `servoloop compare --plot`: both runs' joint trajectories
// overlaid (one colour per joint; the first backend solid, the second dashed)
// in three panels over simulated time — joint position, joint velocity, and
// the position difference (second − first). Drawn by gnuplot (Debian package
// gnuplot-nox, pngcairo terminal) from inline data blocks, so no CSV file is
// written. Non-real-time.
#include <filesystem>
#include <string>
#include <vector>

#include "compare_trajectory.hpp"

namespace servoloop::cli {

struct ComparisonPlot {
  std::filesystem::path png;
  std::string title;
  std::string backend_a;
  std::string backend_b;
  // Per topic: run A's and run B's trajectories and their comparison (same length).
  std::vector<const JointTrajectory*> trajectories_a;
  std::vector<const JointTrajectory*> trajectories_b;
  std::vector<const TopicComparison*> comparisons;
  int width_px = 1200;
  int height_px = 1100;
};

// The gnuplot script. Throws servoloop::Error when there is nothing to plot.
std::string makeComparisonScript(const ComparisonPlot& plot);

// Runs gnuplot on the script and checks the PNG exists. Throws servoloop::Error
// when gnuplot is not installed (naming the package) or fails (its first error line).
void plotComparison(const ComparisonPlot& plot);

}  // namespace servoloop::cli
