// Simulated time on the step grid (hardware_interface/step_grid.hpp) against an independent
// reference: the decimal text of steps × step, written with integer
// arithmetic and read back by strtod (the double nearest to that decimal).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "servoloop/core/step_grid.hpp"

namespace {

using servoloop::snapToStepGrid;
using servoloop::stepsToSeconds;
using servoloop::StepGrid;

// steps × (step_units / 10^digits) as decimal text, e.g. (3131, 1, 3) -> "3.131".
std::string decimalText(std::uint64_t steps, std::uint64_t step_units, int digits) {
  const std::uint64_t units = steps * step_units;
  std::uint64_t scale = 1;
  for (int i = 0; i < digits; ++i) scale *= 10;
  std::string fraction = std::to_string(units % scale);
  fraction.insert(0, static_cast<std::size_t>(digits) - fraction.size(), '0');
  return std::to_string(units / scale) + "." + fraction;
}

double nearestDouble(const std::string& decimal) { return std::strtod(decimal.c_str(), nullptr); }

TEST(StepTime, TheSeedCaseIsTheDecimal) {
  // The product rounds twice; the decimal is 3.131.
  EXPECT_NE(3131 * 0.001, 3.131);
  EXPECT_EQ(stepsToSeconds(3131, 0.001), 3.131);
  EXPECT_EQ(stepsToSeconds(0, 0.001), 0.0);
}

TEST(StepTime, EveryMillisecondStepUpToAnHourIsTheNearestDouble) {
  for (std::uint64_t steps = 0; steps <= 3'600'000; steps += 7) {
    ASSERT_EQ(stepsToSeconds(steps, 0.001), nearestDouble(decimalText(steps, 1, 3))) << steps;
  }
}

TEST(StepTime, OtherDecimalSteps) {
  for (std::uint64_t steps = 0; steps <= 200'000; steps += 3) {
    ASSERT_EQ(stepsToSeconds(steps, 0.0025), nearestDouble(decimalText(steps, 25, 4))) << steps;
    ASSERT_EQ(stepsToSeconds(steps, 0.004), nearestDouble(decimalText(steps, 4, 3))) << steps;
    ASSERT_EQ(stepsToSeconds(steps, 0.02), nearestDouble(decimalText(steps, 2, 2))) << steps;
    ASSERT_EQ(stepsToSeconds(steps, 1e-4), nearestDouble(decimalText(steps, 1, 4))) << steps;
  }
  EXPECT_EQ(stepsToSeconds(7, 2.0), 14.0);
}

TEST(StepTime, AStepThatIsNoShortDecimalIsMultiplied) {
  const double third = 1.0 / 3.0;
  EXPECT_EQ(stepsToSeconds(3000, third), 3000.0 * third);
  EXPECT_EQ(stepsToSeconds(5, 0.0), 0.0);
}

TEST(StepTime, SnapPutsProductsOnTheGridAndLeavesOtherTimes) {
  EXPECT_EQ(snapToStepGrid(3131 * 0.001, 0.001), 3.131);
  EXPECT_EQ(snapToStepGrid(0.0, 0.001), 0.0);
  // A hardware clock that accumulates dt is a few ulps off; still snapped.
  double accumulated = 0.0;
  for (int i = 0; i < 3131; ++i) accumulated += 0.001;
  EXPECT_NE(accumulated, 3.131);
  EXPECT_EQ(snapToStepGrid(accumulated, 0.001), 3.131);
  // Off the grid, or before 0: unchanged.
  EXPECT_EQ(snapToStepGrid(3.1315, 0.001), 3.1315);
  EXPECT_EQ(snapToStepGrid(-0.002, 0.001), -0.002);
}

TEST(StepTime, StepsAtFindsTheWholeNumberOfSteps) {
  const StepGrid grid(0.001);
  std::uint64_t steps = 0;
  double accumulated = 0.0;
  for (int i = 0; i < 3131; ++i) accumulated += 0.001;
  ASSERT_TRUE(grid.stepsAt(accumulated, &steps));
  EXPECT_EQ(steps, 3131u);
  ASSERT_TRUE(grid.stepsAt(0.0, &steps));
  EXPECT_EQ(steps, 0u);
  // Half a step is no grid point, and neither is anything before 0 or a NaN.
  EXPECT_FALSE(grid.stepsAt(3.1315, &steps));
  EXPECT_FALSE(grid.stepsAt(-0.001, &steps));
  EXPECT_FALSE(grid.stepsAt(std::nan(""), &steps));
  // A grid without a usable step has no points.
  EXPECT_FALSE(StepGrid(0.0).stepsAt(1.0, &steps));
}

}  // namespace
