#pragma once
// The benchmark functions benchmarks 2 and 5 share: one iteration is one
// whole episode (a fresh robot, then RobotCase::steps_per_episode physics
// steps), each on its own heap placement (HeapPlacementShuffle).
#include <cstdint>

#include <benchmark/benchmark.h>

#include "bench_support.hpp"
#include "loop_fixtures.hpp"
#include "median_reporter.hpp"

namespace servoloop::bench {

// A raw loop (RawBulletPd, RawMujocoPd): one step without effort before the
// timed steps, as the servoloop loop's switch cycle.
template <typename RawLoop>
void rawEpisodes(benchmark::State& state, const RobotCase* robot) {
  const HeapPlacementShuffle placement;
  RawLoop raw(*robot);
  raw.stepWithoutControl();
  for (auto _ : state) {
    for (std::uint64_t k = 0; k < robot->steps_per_episode; ++k) raw.step();
  }
  state.counters[kUnitsPerIterationCounter] = static_cast<double>(robot->steps_per_episode);
  state.counters["q_first_end"] = raw.jointPosition(0);
  state.counters["max_abs_q_end"] = raw.maxAbsJointPosition();
}

// The whole servoloop loop on the robot_hw plugin `backend`.
inline void servoloopEpisodes(benchmark::State& state, const RobotCase* robot, const char* backend) {
  const HeapPlacementShuffle placement;
  ServoloopSimulation simulation(*robot, backend);
  for (auto _ : state) simulation.runSteps(robot->steps_per_episode);
  if (simulation.stepsTaken() != robot->steps_per_episode + 1) state.SkipWithError("wrong number of steps");
  if (simulation.hardwareErrors() != 0) state.SkipWithError("hardware errors during the run");
  state.counters[kUnitsPerIterationCounter] = static_cast<double>(robot->steps_per_episode);
  state.counters["q_first_end"] = simulation.firstJointPosition();
}

}  // namespace servoloop::bench
