#pragma once
// Simulated time on the physics step grid, exact to the decimal the user wrote.
//
// Simulated time is a whole number of physics steps times the step. Computed
// as steps × step in doubles, that product is rounded twice (the step itself,
// 0.001, is not a double): 3131 × 0.001 gives 3.1310000000000002, which then
// shows in every stamp, CSV row and `topic echo`. When the step is a short
// decimal (m / 10^k with small k, as every world.time_step written in a launch
// file is), the time is computed as (steps · m) / 10^k instead: an exact
// integer divided by an exact power of ten, rounded once, so it is the double
// nearest to the decimal value and prints as 3.131.
//
// StepGrid finds m and 10^k once, when it is built; its conversions are then
// a multiplication and a division, cheap enough for every control cycle.
// Real-time safe: no allocation, no exception.
#include <cmath>
#include <cstdint>

namespace servoloop {

class StepGrid {
 public:
  // A grid of `step_s` seconds. A step that is not a positive, finite number
  // gives a grid whose conversions are plain steps × step_s.
  explicit StepGrid(double step_s) noexcept;

  double step() const noexcept { return step_s_; }

  // The simulated time after `steps` physics steps: the double nearest to
  // steps × (the shortest decimal of the step) when the step is a decimal with
  // at most 15 digits after the point and steps · m stays below 2^53;
  // otherwise steps × step.
  double seconds(std::uint64_t steps) const noexcept {
    if (power_ > 0.0 && steps <= max_exact_steps_) return static_cast<double>(steps) * mantissa_ / power_;
    return static_cast<double>(steps) * step_s_;
  }

  // `time_s` put onto the grid (seconds() of the nearest whole number of
  // steps) when it lies within a millionth of a step of a grid point at or
  // after 0; any other time is returned unchanged.
  double snap(double time_s) const noexcept {
    std::uint64_t steps = 0;
    return stepsAt(time_s, &steps) ? seconds(steps) : time_s;
  }

  // Whether `time_s` lies within a millionth of a step of a grid point at or
  // after 0, and if so, that point's number of steps.
  bool stepsAt(double time_s, std::uint64_t* steps) const noexcept {
    if (!(time_s >= 0.0) || !(time_s <= max_snap_time_s_)) return false;
    // The nearest whole number of steps, as x + 0.5 truncated (x >= 0 and
    // below 2^53 here; at a tie both neighbours are half a step away, so
    // neither is taken). Near a grid point (the only case that counts) the
    // product rounds like the quotient: both are within a millionth of the
    // same integer.
    const auto nearest = static_cast<std::int64_t>(time_s * inverse_step_ + 0.5);
    if (std::abs(static_cast<double>(nearest) * step_s_ - time_s) > snap_tolerance_s_) return false;
    *steps = static_cast<std::uint64_t>(nearest);
    return true;
  }

 private:
  // Every integer up to 2^53 is a double; products below it are exact.
  static constexpr double kExactIntegerLimit = 9007199254740992.0;

  double step_s_;
  double inverse_step_ = 0.0;  // 1 / step_s; 0 when the step is not positive and finite
  double max_snap_time_s_ = -1.0;  // 2^53 steps; negative (nothing snaps) without inverse_step_
  double snap_tolerance_s_ = 0.0;  // a millionth of a step
  double mantissa_ = 0.0;  // m, with step_s == m / power_; 0 when the step is no short decimal
  double power_ = 0.0;     // 10^k
  std::uint64_t max_exact_steps_ = 0;
};

// One-off conversions (each builds a StepGrid).
inline double stepsToSeconds(std::uint64_t steps, double step_s) noexcept { return StepGrid(step_s).seconds(steps); }
inline double snapToStepGrid(double time_s, double step_s) noexcept { return StepGrid(step_s).snap(time_s); }

}  // namespace servoloop
