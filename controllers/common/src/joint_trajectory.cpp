#include "servoloop/controllers/common/joint_trajectory.hpp"

#include <cmath>

#include "servoloop/controllers/common/angles.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::controllers {
namespace {

void checkPoint(const TrajectoryPoint& point, std::size_t index, std::size_t joints, double previous_time) {
  const std::string where = "trajectory point " + std::to_string(index);
  const auto check = [&](const std::vector<double>& values, const char* field, bool may_be_empty) {
    if (values.empty() && may_be_empty) return;
    if (values.size() != joints) {
      throw Error(where + ": " + field + " has " + std::to_string(values.size()) + " values for " +
                  std::to_string(joints) + " joints; give one per joint" +
                  (may_be_empty ? " or none" : ""));
    }
    for (std::size_t j = 0; j < values.size(); ++j) {
      if (!std::isfinite(values[j])) {
        throw Error(where + ": " + field + "[" + std::to_string(j) + "] is not a finite number");
      }
    }
  };
  check(point.positions, "positions", false);
  check(point.velocities, "velocities", true);
  check(point.accelerations, "accelerations", true);
  if (!point.accelerations.empty() && point.velocities.empty()) {
    throw Error(where + ": accelerations without velocities; give velocities too (0 for none)");
  }
  if (!std::isfinite(point.time_from_start) || !(point.time_from_start > previous_time)) {
    throw Error(where + ": time_from_start " + std::to_string(point.time_from_start) +
                " must be finite and after the previous point's (" + std::to_string(previous_time) + " s)");
  }
}

SplineKind kindOf(const TrajectoryPoint& point) {
  if (!point.accelerations.empty()) return SplineKind::quintic;
  if (!point.velocities.empty()) return SplineKind::cubic;
  return SplineKind::linear;
}

JointSample stateOf(const TrajectoryPoint& point, std::size_t joint, double offset) {
  return {point.positions[joint] + offset, point.velocities.empty() ? 0.0 : point.velocities[joint],
          point.accelerations.empty() ? 0.0 : point.accelerations[joint]};
}

}  // namespace

JointTrajectory JointTrajectory::build(double now, double start_time, const std::vector<JointSample>& current,
                                       const std::vector<TrajectoryPoint>& points,
                                       const std::vector<bool>& continuous) {
  const std::size_t joints = current.size();
  if (!continuous.empty() && continuous.size() != joints) {
    throw Error("JointTrajectory: " + std::to_string(continuous.size()) + " continuous flags for " +
                std::to_string(joints) + " joints");
  }
  const double start = start_time > 0.0 ? start_time : now;
  double previous = -INFINITY;
  for (std::size_t i = 0; i < points.size(); ++i) {
    checkPoint(points[i], i, joints, previous);
    previous = points[i].time_from_start;
  }

  JointTrajectory trajectory;
  trajectory.end_time_ = now;
  std::size_t first = 0;
  while (first < points.size() && !(start + points[first].time_from_start > now)) ++first;
  trajectory.dropped_points_ = first;
  if (first == points.size()) return trajectory;

  trajectory.segments_.resize(joints);
  for (std::size_t j = 0; j < joints; ++j) {
    // Whole turns that bring the first point the short way round.
    double offset = 0.0;
    if (!continuous.empty() && continuous[j]) {
      const double target = points[first].positions[j];
      offset = current[j].position + shortestAngularDistance(current[j].position, target) - target;
    }
    std::vector<SplineSegment>& segments = trajectory.segments_[j];
    segments.reserve(points.size() - first);
    double from_time = now;
    JointSample from = current[j];
    for (std::size_t i = first; i < points.size(); ++i) {
      const double to_time = start + points[i].time_from_start;
      const JointSample to = stateOf(points[i], j, offset);
      segments.emplace_back(from_time, from, to_time, to, kindOf(points[i]));
      from_time = to_time;
      from = to;
    }
  }
  trajectory.end_time_ = start + points.back().time_from_start;
  return trajectory;
}

void JointTrajectory::sample(double time, std::vector<JointSample>& out) const noexcept {
  for (std::size_t j = 0; j < segments_.size() && j < out.size(); ++j) {
    const std::vector<SplineSegment>& segments = segments_[j];
    if (segments.empty()) continue;
    // The segment that runs at `time`: the last one starting at or before it
    // (the first before the start; the last after the end).
    std::size_t lo = 0;
    std::size_t hi = segments.size();
    while (hi - lo > 1) {
      const std::size_t mid = (lo + hi) / 2;
      if (segments[mid].startTime() <= time) lo = mid;
      else hi = mid;
    }
    out[j] = segments[lo].sample(time);
  }
}

}  // namespace servoloop::controllers
