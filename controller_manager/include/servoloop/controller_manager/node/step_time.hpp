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
// Lives with the node, whose robots' loops stamp their messages with it;
// SimulationLoop uses it for the time it hands to the hardware, controllers
// and bus. Real-time safe: no allocation, no exception, a few dozen flops.
#include <cstdint>

namespace servoloop::controller_manager::node {

// The simulated time after `steps` physics steps of `step_s` seconds: the
// double nearest to steps × (the shortest decimal of step_s) when step_s is a
// decimal with at most 15 digits after the point and the product stays below
// 2^53; otherwise steps × step_s.
double stepsToSeconds(std::uint64_t steps, double step_s) noexcept;

// `time_s` put onto the step grid (stepsToSeconds of the nearest whole number
// of steps) when it lies within a millionth of a step of a grid point at or
// after 0; any other time is returned unchanged.
double snapToStepGrid(double time_s, double step_s) noexcept;

}  // namespace servoloop::controller_manager::node
